// `tessera march`: renders one frame of a ray-marched scene (terrain, 16-sine noise,
// value-noise volume, gradient-noise surface, metaballs) with background and fog, through the rasterizer's tile stage, and
// writes it as an image.
//
//   tessera march --scene metaballs --kernel blinn --balls 6 --time 2.5 -o blobs.png
//   tessera march --scene terrain --strategy geometric --fog-density 0.01 --fog-falloff 0.3
//                 --fog-colour 0.7,0.75,0.8 --size 1920x1080 -o terrain.exr
//   tessera march --scene metaballs --reflectivity 0.6 --cube-map 'media/sky_{face}.png' -o m.png
#include <chrono>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "examples/command.h"
#include "raster/core/atomic_file.h"
#include "raster/march/march_scene.h"
#include "raster/output/frame_encoding.h"
#include "raster/pipeline/rasterizer.h"

namespace tessera::cli {
namespace {

// "0.5" (grey) or "0.5,0.6,0.7".
glm::vec3 parse_rgb(const std::string& text, const char* flag) {
    std::vector<float> values;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');) {
        try {
            size_t used = 0;
            values.push_back(std::stof(part, &used));
            if (used != part.size()) throw std::invalid_argument(part);
        } catch (const std::exception&) {
            throw UsageError(std::string(flag) + " expects a number or R,G,B, got '" + text + "'");
        }
    }
    if (values.size() == 1) return glm::vec3(values[0]);
    if (values.size() == 3) return {values[0], values[1], values[2]};
    throw UsageError(std::string(flag) + " expects a number or R,G,B, got '" + text + "'");
}

struct MarchOptions {
    std::string scene = "metaballs", kernel = "wyvill", strategy = "uniform", normals = "analytic";
    std::string size = "960x540", output = "march.png";
    std::string fog_density = "0", fog_colour = "0.6,0.65,0.7";
    std::string cube_map;
    int balls = 5, steps = 128, threads = 0;
    float time = 0.0f, max_step = 0.0f, tolerance = 1e-3f, normal_step = 0.05f;
    float fog_falloff = 0.0f, fog_base = 0.0f, reflectivity = 0.0f;
    bool no_refine = false;
};

Run define_march(CLI::App& root) {
    auto o = std::make_shared<MarchOptions>();
    CLI::App* cmd = root.add_subcommand("march", "render a ray-marched implicit surface with fog");
    cmd->add_option("--scene", o->scene, "terrain | sine-noise | noise-volume | gradient-noise | metaballs")->capture_default_str();
    cmd->add_option("--time", o->time, "animation time in seconds")->capture_default_str();
    cmd->add_option("--kernel", o->kernel, "metaball kernel: blinn | perlin | wyvill")->capture_default_str();
    cmd->add_option("--balls", o->balls, "metaball count (at least 3)")->capture_default_str();
    cmd->add_option("--steps", o->steps, "march steps per ray")->capture_default_str();
    cmd->add_option("--strategy", o->strategy, "uniform | geometric (+2 % per step)")->capture_default_str();
    cmd->add_option("--max-step", o->max_step, "cap on the uniform step (0: none; 0.05 suits a unit-thick slab)");
    cmd->add_option("--tolerance", o->tolerance, "bisection tolerance in world units")->capture_default_str();
    cmd->add_flag("--no-refine", o->no_refine, "skip the bisection after the first sign change");
    cmd->add_option("--normals", o->normals, "analytic | differences")->capture_default_str();
    cmd->add_option("--normal-step", o->normal_step, "central-difference step h")->capture_default_str();
    cmd->add_option("--reflectivity", o->reflectivity, "mirror share of the background, 0..1")->capture_default_str();
    cmd->add_option("--fog-density", o->fog_density, "fog extinction per unit: a number or R,G,B (0: no fog)")->capture_default_str();
    cmd->add_option("--fog-colour", o->fog_colour, "fog colour (0: black fog)")->capture_default_str();
    cmd->add_option("--fog-falloff", o->fog_falloff, "height falloff b of exp(-b (y - base)); 0: constant fog")->capture_default_str();
    cmd->add_option("--fog-base", o->fog_base, "height where the fog has its nominal density")->capture_default_str();
    cmd->add_option("--cube-map", o->cube_map,
                    "six images as the background, '{face}' standing for px nx py ny pz nz "
                    "(e.g. 'sky/{face}.png'; default: procedural sky)");
    cmd->add_option("--size", o->size, "WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("-o,--output", o->output, "image file (.png, .exr, .tif)")->capture_default_str();
    add_threads_option(*cmd, o->threads);
    return [o] {
        int width = 0, height = 0;
        parse_size(o->size, "--size", width, height);
        march::MarchSceneSettings s;
        s.kind = march::parse_march_scene(o->scene);
        s.time = o->time;
        s.balls = o->balls;
        if (o->kernel == "blinn") s.kernel = march::MetaballKernel::blinn;
        else if (o->kernel == "perlin") s.kernel = march::MetaballKernel::perlin;
        else if (o->kernel == "wyvill") s.kernel = march::MetaballKernel::wyvill;
        else throw UsageError("--kernel expects blinn, perlin or wyvill, got '" + o->kernel + "'");
        if (o->strategy == "geometric") s.march.strategy = march::StepStrategy::geometric;
        else if (o->strategy != "uniform")
            throw UsageError("--strategy expects uniform or geometric, got '" + o->strategy + "'");
        s.march.steps = o->steps;
        if (o->max_step != 0.0f) s.march.max_step = o->max_step;
        s.march.tolerance = o->tolerance;
        s.march.refine = !o->no_refine;
        if (o->normals == "differences") s.normals.method = march::NormalMethod::central_differences;
        else if (o->normals != "analytic")
            throw UsageError("--normals expects analytic or differences, got '" + o->normals + "'");
        s.normals.h = o->normal_step;
        if (!(o->reflectivity >= 0.0f && o->reflectivity <= 1.0f))
            throw UsageError("--reflectivity must be in 0..1");
        s.material.reflectivity = o->reflectivity;
        s.fog.density = parse_rgb(o->fog_density, "--fog-density");
        s.fog.colour = parse_rgb(o->fog_colour, "--fog-colour");
        s.fog.falloff = o->fog_falloff;
        s.fog.base_height = o->fog_base;
        if (!output::frame_format_supported(o->output))
            throw UsageError("--output: no image writer for '" + o->output + "'");
        check_writable(o->output);  // before the render, not after it

        if (!o->cube_map.empty()) {
            s.background.kind = scene::Background::Kind::cube_map;
            s.background.cube = scene::load_cube_map(o->cube_map);
        }

        const auto threads = limit_threads(o->threads);
        const auto start = std::chrono::steady_clock::now();
        const march::MarchScene scene(s, width, height);
        const std::vector<pipeline::TilePass> passes = scene.passes();
        pipeline::Rasterizer rasterizer;
        VisibilityBuffer visibility;
        Frame frame(width, height);
        rasterizer.render(Mesh{}, scene.camera().view_projection(), pipeline::Viewport(width, height), pipeline::RasterOptions{},
                          visibility, passes, &frame.pixels);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        output::write_frame(o->output, frame);
        std::printf("wrote %s (%dx%d, %s, %.1f ms render)\n", o->output.c_str(), width, height, o->scene.c_str(), ms);
        return 0;
    };
}

TESSERA_COMMAND(40, define_march);

}  // namespace
}  // namespace tessera::cli
