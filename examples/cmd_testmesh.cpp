// `tessera testmesh`: writes the procedural test meshes of raster/test_meshes.h as OBJ (plus
// the matching camera file), so that other renderers (the llvmpipe comparison) run the very
// meshes the rasterizer benchmarks use.
//
//   tessera testmesh --kind fillrate --leg 10 --count 1048576 --size 1920x1080
//       --out fill10.obj --camera-out fill10.cam
//   tessera testmesh --kind sphere --count 1000000 --out sphere.obj --camera-out sphere.cam
//   tessera testmesh --kind spheres --count 100000 --out grid.obj --camera-out grid.cam
#include <cmath>
#include <cstdio>
#include <string>

#include "examples/command.h"
#include "raster/core/atomic_file.h"
#include "raster/core/camera.h"
#include "raster/io/obj_loader.h"
#include "raster/workloads/sphere_grid.h"
#include "raster/workloads/test_meshes.h"

namespace tessera::cli {
namespace {

struct Options {
    std::string kind = "sphere", size = "1920x1080", out, camera_out;
    double leg = 10;
    size_t count = 100000;
    uint64_t seed = 7;
};

std::string camera_text(const Camera& c) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "eye %.9g %.9g %.9g\nlookat %.9g %.9g %.9g\nup %.9g %.9g %.9g\nfovy_deg %.9g\nnear %.9g\nfar %.9g\n",
                  c.eye.x, c.eye.y, c.eye.z, c.lookat.x, c.lookat.y, c.lookat.z, c.up.x, c.up.y, c.up.z,
                  c.fovy_deg, c.near, c.far);
    return text;
}

int run(const Options& o) {
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    check_writable(o.out);  // both outputs before the mesh: neither is written if one cannot be
    if (!o.camera_out.empty()) check_writable(o.camera_out);
    Camera camera;
    camera.aspect = float(width) / float(height);
    Mesh mesh;
    if (o.kind == "sphere") {
        // The benchmark sphere (bench_raster.cpp): about `count` triangles filling the view.
        const int rings = std::max(4, int(std::sqrt(double(o.count) / 4.0)));
        const int segments = std::max(3, int(o.count / (2 * size_t(rings - 1))));
        mesh = workloads::sphere(segments, rings);
        camera.eye = {0.0f, 0.4f, 2.6f};
        camera.fovy_deg = 50.0f;
    } else if (o.kind == "spheres") {
        // The sphere-grid scene (sphere_grid.h): a ground plane under a grid of spheres,
        // about `count` triangles, seen from above so that most pixels are covered.
        workloads::SphereGridScene scene = workloads::make_sphere_grid(o.count, camera.aspect);
        mesh = std::move(scene.mesh);
        camera = scene.camera;
    } else if (o.kind == "fillrate" || o.kind == "random") {
        const auto window = o.kind == "fillrate"
                                ? workloads::fill_rate(o.seed, o.count, float(o.leg), width, height)
                                : workloads::random_triangles(o.seed, o.count, width, height, float(o.leg));
        mesh = workloads::to_world(window, camera.view_projection(), width, height);
    } else {
        throw UsageError("--kind expects sphere, spheres, fillrate or random, got '" + o.kind + "'");
    }
    io::write_obj(o.out, mesh);
    if (!o.camera_out.empty()) write_file_atomically(o.camera_out, camera_text(camera));
    std::printf("wrote %s: %zu vertices, %zu triangles\n", o.out.c_str(), mesh.vertex_count(), mesh.triangle_count());
    return 0;
}

Run define_testmesh(CLI::App& root) {
    auto options = std::make_shared<Options>();
    Options& o = *options;
    CLI::App* cmd = root.add_subcommand("testmesh", "write a procedural benchmark/test mesh as OBJ");
    cmd->add_option("--kind", o.kind, "sphere | spheres (a grid of spheres on a ground plane) | fillrate (MSOC-style right triangles) | random")->default_val("sphere");
    cmd->add_option("--count", o.count, "number of triangles (about, for sphere)")->check(CLI::Range(size_t(1), size_t(1) << 27));
    cmd->add_option("--leg", o.leg, "fillrate: leg length in pixels; random: max edge length")->check(CLI::Range(0.5, 8192.0));
    cmd->add_option("--size", o.size, "image size the screen-space kinds are laid out for")->default_val("1920x1080");
    cmd->add_option("--seed", o.seed, "random seed");
    cmd->add_option("--out", o.out, "OBJ file to write")->required();
    cmd->add_option("--camera-out", o.camera_out, "camera file (tessera raster --camera) to write");
    return [options] { return run(*options); };
}

TESSERA_COMMAND(21, define_testmesh);

}  // namespace
}  // namespace tessera::cli
