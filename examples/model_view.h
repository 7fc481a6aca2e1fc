// A model file as the commands show it (`tessera raster`, `tessera compare --mesh`):
// - load_model_mesh: one mesh for the conformance shades (id, depth, normal, phong), OBJ
//   through the OBJ loader as always (its triangle order is a contract with the llvmpipe peer),
//   every other format through the importer with its parts merged in order;
// - load_model_view: the model with its materials as a scene (asset::import_model), a camera
//   from the flags or framing it, and the default light rig.
// Import warnings go to stderr as "tessera: warning: ..." lines.
#pragma once
#include <cstdint>
#include <string>

#include "examples/command.h"
#include "raster/core/mesh.h"
#include "raster/io/model_file.h"
#include "raster/io/obj_loader.h"
#include "raster/scene/scene.h"

namespace tessera::cli {

struct ModelMesh {
    Mesh mesh;
    std::optional<Box> box;    // of the triangles' corners; none for an empty mesh
    bool obj = false;          // read by the OBJ loader (obj_stats), else by the importer
    io::ObjLoadStats obj_stats;
    io::ModelStats model_stats;
};
ModelMesh load_model_mesh(const std::string& path);

struct ModelView {
    scene::Scene scene;  // camera set (aspect width / height), lights: the default rig
    Box box;
    io::ModelStats stats;
    uint64_t triangles = 0;
};
ModelView load_model_view(const std::string& path, const CameraFlags& flags, int width, int height);

}  // namespace tessera::cli
