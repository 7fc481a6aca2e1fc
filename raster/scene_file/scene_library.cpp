#include "raster/scene_file/scene_library.h"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <stdexcept>

namespace tessera::scene_file {

namespace fs = std::filesystem;

std::vector<fs::path> scene_directories(const fs::path& built_in, const fs::path& executable) {
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("TESSERA_SCENE_PATH")) {
        std::string list = env;
        size_t start = 0;
        while (start <= list.size()) {
            const size_t end = std::min(list.find(':', start), list.size());
            if (end > start) candidates.emplace_back(list.substr(start, end - start));
            start = end + 1;
        }
    }
    if (!built_in.empty()) candidates.push_back(built_in);
    if (!executable.empty()) {
        const fs::path bin = executable.parent_path();
        candidates.push_back(bin / ".." / "share" / "tessera" / "scenes");
        candidates.push_back(bin / "scenes");
    }
    std::vector<fs::path> out;
    std::error_code ec;
    for (const fs::path& c : candidates) {
        if (!fs::is_directory(c, ec)) continue;
        const fs::path canonical = fs::weakly_canonical(c, ec);
        if (std::find(out.begin(), out.end(), canonical) == out.end()) out.push_back(canonical);
    }
    return out;
}

std::vector<std::string> available_scenes(const std::vector<fs::path>& directories) {
    std::set<std::string> names;
    std::error_code ec;
    for (const fs::path& dir : directories)
        for (const auto& entry : fs::directory_iterator(dir, ec))
            if (entry.path().extension() == ".json") names.insert(entry.path().stem().string());
    return {names.begin(), names.end()};
}

fs::path find_scene(const std::string& name, const std::vector<fs::path>& directories) {
    if (name.size() > 5 && name.ends_with(".json")) return name;
    if (name.find('/') != std::string::npos) return name;
    std::error_code ec;
    for (const fs::path& dir : directories)
        if (fs::is_regular_file(dir / (name + ".json"), ec)) return dir / (name + ".json");
    std::string list;
    for (const std::string& n : available_scenes(directories)) list += (list.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown scene '" + name + "' (available: " + (list.empty() ? "none found" : list) +
                                "; or give a FILE.json)");
}

}  // namespace tessera::scene_file
