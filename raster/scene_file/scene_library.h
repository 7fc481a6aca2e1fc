// Finding scene files by name: `tessera render --scene snakes` looks for snakes.json in the
// scene directories, in order: $TESSERA_SCENE_PATH (colon-separated), the source tree's
// examples/scenes (compiled in, for a build tree), and next to an installed binary
// (<bin>/../share/tessera/scenes, <bin>/scenes). A name ending in ".json" or containing a
// '/' is a file path instead.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace tessera::scene_file {

// The directories above that exist, in search order, without duplicates.
std::vector<std::filesystem::path> scene_directories(const std::filesystem::path& built_in,
                                                     const std::filesystem::path& executable);

// Names (file stems) of the *.json files in `directories`, sorted, first occurrence wins.
std::vector<std::string> available_scenes(const std::vector<std::filesystem::path>& directories);

// The file for `name_or_path`. Throws std::invalid_argument for an unknown name, listing the
// available scenes.
std::filesystem::path find_scene(const std::string& name_or_path,
                                 const std::vector<std::filesystem::path>& directories);

}  // namespace tessera::scene_file
