// Fuzz target: the JSON scene reader (raster/scene_file/scene_parse.h) on arbitrary text.
// Accepted scenes must come with a usable animation (fps > 0, first <= last), a positive
// default size, and a camera that can be placed at the first and last frame without throwing
// anything but the documented invalid_argument. Building the scene (reaction-diffusion,
// heightfields) is left out: it is bounded by the parser's ranges and too slow to fuzz.
#include <cmath>
#include <stdexcept>

#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"
#include "tests/fuzz/fuzz_target.h"

namespace tessera::fuzz {

std::string scene_input(Bytes data) {
    const std::string text(reinterpret_cast<const char*>(data.data()), data.size());
    std::vector<std::string> warnings;
    scene_file::SceneSpec spec;
    try {
        spec = scene_file::parse_scene(text, "fuzz.json", warnings);
    } catch (const scene_file::SceneFileError&) {
        return "";  // rejected with "FILE: /pointer: problem": expected for bad files
    }
    for (const std::string& w : warnings)
        if (w.find('\n') != std::string::npos) return "a warning spans more than one line";
    if (!(spec.animation.fps > 0.0f) || !std::isfinite(spec.animation.fps)) return "accepted a non-positive fps";
    if (spec.animation.first > spec.animation.last) return "accepted a reversed frame range";
    if (spec.size.x < 1 || spec.size.y < 1) return "accepted a non-positive size";
    for (int frame : {spec.animation.first, spec.animation.last}) {
        try {
            const Camera c = render::camera_at(spec.camera, float(frame) / spec.animation.fps, 16.0f / 9.0f);
            (void)c.view_projection();
        } catch (const std::invalid_argument&) {
        }
    }
    return "";
}

}  // namespace tessera::fuzz

TESSERA_FUZZ_ENTRY(scene_input)
