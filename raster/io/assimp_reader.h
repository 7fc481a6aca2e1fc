// The one place that talks to Assimp: reads a model file with the post-processing tessera
// needs and copies what tessera uses out of Assimp's scene (raw_model.h). model_file.h runs it
// in a child process; nothing else should call it directly.
#pragma once
#include <filesystem>

#include "raster/io/raw_model.h"

namespace tessera::io {

// Throws tessera::Error with Assimp's one-line reason when it rejects the file.
RawModel read_with_assimp(const std::filesystem::path& path);

// True when Assimp has a reader for this extension (".glb", ".PLY": any case, with the dot).
bool assimp_reads_extension(const std::string& extension);

}  // namespace tessera::io
