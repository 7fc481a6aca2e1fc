// Reading a JSON scene file into a SceneSpec (scene_spec.h). The format, by example, is in
// examples/scenes/*.json; every key is documented where it is read in scene_parse.cpp.
//
// Diagnostics: a missing file, malformed JSON (with line and column) or a value of the wrong
// type or range throws SceneFileError "FILE: /json/pointer: problem"; unknown keys and
// material parameters the chosen shading model does not use are warnings ("a
// warning, not an error"), returned as "FILE: /json/pointer: ..." lines.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "raster/scene_file/scene_file_error.h"
#include "raster/scene_file/scene_spec.h"

namespace tessera::scene_file {

// `label` names the source in messages (the path as the user wrote it).
SceneSpec parse_scene(const std::string& json_text, const std::string& label,
                      std::vector<std::string>& warnings);

SceneSpec load_scene_file(const std::filesystem::path& path, std::vector<std::string>& warnings);

}  // namespace tessera::scene_file
