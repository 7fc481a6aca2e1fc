#include "examples/model_view.h"

#include <cstdio>

#include "raster/asset/light_rig.h"
#include "raster/asset/model_import.h"

namespace tessera::cli {
namespace {

bool is_obj(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".obj";
}

void warn(const std::vector<std::string>& warnings) {
    for (const std::string& w : warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
}

// The bounds of the corners of the mesh's triangles (the OBJ loader parks bad vertices at the
// origin in triangles it makes degenerate: those are left out).
std::optional<Box> triangle_bounds(const Mesh& mesh) {
    std::optional<Box> box;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t* i = &mesh.indices[3 * t];
        if (i[0] == i[1] && i[1] == i[2]) continue;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = mesh.positions[i[k]];
            if (!box) box = Box{p, p};
            box->lower = glm::min(box->lower, p);
            box->upper = glm::max(box->upper, p);
        }
    }
    return box;
}

}  // namespace

ModelMesh load_model_mesh(const std::string& path) {
    ModelMesh out;
    out.obj = is_obj(path);
    if (out.obj) {
        out.mesh = io::load_obj(path, &out.obj_stats);
    } else {
        const io::ModelFile model = io::read_model(path);
        warn(model.warnings);
        out.model_stats = model.stats;
        out.mesh = io::merge_parts(model);
    }
    out.box = triangle_bounds(out.mesh);
    return out;
}

ModelView load_model_view(const std::string& path, const CameraFlags& flags, int width, int height) {
    asset::ImportedModel model = asset::import_model(path);
    warn(model.warnings);
    ModelView view;
    view.box = Box{model.lower, model.upper};
    view.stats = model.stats;
    view.triangles = model.stats.triangles;
    view.scene.camera = make_camera_or_frame(flags, width, height, view.box);
    view.scene.lights = asset::default_light_rig(view.scene.camera, model.lower, model.upper);
    asset::add_to_scene(view.scene, std::move(model), scene::Transform{}, std::filesystem::path(path).filename().string());
    return view;
}

}  // namespace tessera::cli
