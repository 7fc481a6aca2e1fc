// What `tessera compare` measured, and the two ways it is shown: a table on the terminal and
// a JSON file with the same figures (rounded the same way, so a script can check one against
// the other) plus the facts that make them reproducible: machine, command line, date.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raster/render/crossover.h"
#include "raster/render/renderer_comparison.h"

namespace tessera::cli {

// One renderer's whole frames (FrameRenderer, no shadows), medians over the repeats.
struct RendererFigures {
    double visibility_ms = 0;  // tile rasterizer stages | Embree primary rays
    double shading_ms = 0;     // the tile passes after visibility (shading, blending, compute passes)
    // The BVH work of a frame after the first (raytrace only): the frame renderer keeps the
    // BVHs of objects that did not move, so for still content this is the check that nothing did.
    double bvh_ms = 0;
    double frame_ms = 0;       // the whole frame, bake included
    double peak_resident_mib = 0;
};

struct ShadowFigures {
    size_t lights = 0;
    double maps_ms = 0, rays_ms = 0;  // medians
    shadow::MaskAgreement all, non_grazing;
};

// One --size and --threads combination.
struct ConfigFigures {
    int width = 0, height = 0;
    int threads = 0;  // what ran: --threads N capped by the machine, or every core for 0
    RendererFigures raster, raytrace;
    render::IdAgreement ids;
    render::BvhTimes bvh;                 // medians
    std::optional<ShadowFigures> shadows;  // when the content has lights (at most 4)
};

// One --sweep count: N copies of the content, framed as a whole, at the first size and thread
// count.
struct SweepPoint {
    int copies = 0;
    uint64_t triangles = 0;
    RendererFigures raster, raytrace;
};

struct ComparisonReport {
    std::string content;  // the --mesh or --scene argument
    uint64_t triangles = 0;
    size_t lights = 0;
    int repeat = 0;
    bool peak_per_renderer = true;  // false: the peaks are the process's (no /proc/self/clear_refs)
    std::vector<ConfigFigures> configs;
    std::vector<SweepPoint> sweep;
    // Raster against raytrace over the sweep: whole frames, and visibility alone (the ray
    // caster's BVH left out, as a static scene that keeps its BVH pays).
    std::optional<render::Crossover> frame_crossover, visibility_crossover;
    // Facts for the JSON file.
    std::string command, date, cpu, simd;
    unsigned hardware_threads = 0;
};

// The crossovers of report.sweep (raster = a, raytrace = b).
void find_crossovers(ComparisonReport& report);

void print_report(const ComparisonReport& report);

// The report as JSON text (schema in README "Benchmark your own scene").
std::string report_json(const ComparisonReport& report);

}  // namespace tessera::cli
