#include "examples/compare_report.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace tessera::cli {
namespace {

// Milliseconds with 3 decimals, MiB with 1, percentages with 4: the table and the JSON file
// both show these rounded numbers, so that what a script reads is what the user saw.
double ms3(double ms) { return std::round(ms * 1000.0) / 1000.0; }
double mib1(double mib) { return std::round(mib * 10.0) / 10.0; }
double percent(double fraction) { return std::round(fraction * 1e6) / 1e4; }  // 4 decimals

// `rays_faster`: whether the ray caster won at the sweep's largest count.
void print_crossover(const char* what, const std::optional<render::Crossover>& c, const ComparisonReport& r,
                     bool rays_faster) {
    if (c) {
        std::printf("  crossover (%s): %.0f triangles; %s is faster above\n", what, c->triangles,
                    c->b_faster_above ? "raytrace" : "raster");
        return;
    }
    std::printf("  crossover (%s): none from %llu to %llu triangles; %s is faster throughout\n", what,
                (unsigned long long)r.sweep.front().triangles, (unsigned long long)r.sweep.back().triangles,
                rays_faster ? "raytrace" : "raster");
}

nlohmann::json renderer_json(const RendererFigures& f, bool rays) {
    nlohmann::json j = {{"visibility_ms", ms3(f.visibility_ms)},
                        {"shading_ms", ms3(f.shading_ms)},
                        {"frame_ms", ms3(f.frame_ms)},
                        {"peak_resident_mib", mib1(f.peak_resident_mib)}};
    if (rays) j["bvh_ms"] = ms3(f.bvh_ms);
    return j;
}

nlohmann::json agreement_json(const shadow::MaskAgreement& a) {
    return {{"compared_pixels", a.compared}, {"differ_pixels", a.differ}, {"agree_percent", percent(a.agreement())}};
}

nlohmann::json crossover_json(const std::optional<render::Crossover>& c) {
    if (!c) return nullptr;
    return {{"triangles", std::round(c->triangles)}, {"faster_above", c->b_faster_above ? "raytrace" : "raster"}};
}

}  // namespace

void find_crossovers(ComparisonReport& report) {
    std::vector<render::CostSample> frames, visibility;
    for (const SweepPoint& p : report.sweep) {
        frames.push_back({double(p.triangles), p.raster.frame_ms, p.raytrace.frame_ms});
        visibility.push_back({double(p.triangles), p.raster.visibility_ms, p.raytrace.visibility_ms});
    }
    report.frame_crossover = render::find_crossover(frames);
    report.visibility_crossover = render::find_crossover(visibility);
}

void print_report(const ComparisonReport& r) {
    std::printf("tessera compare: %s: %llu triangles, %zu light(s); medians of %d run(s)\n", r.content.c_str(),
                (unsigned long long)r.triangles, r.lights, r.repeat);
    for (const ConfigFigures& c : r.configs) {
        char config[64];
        std::snprintf(config, sizeof config, "%dx%d, %d thread(s)", c.width, c.height, c.threads);
        std::printf("%-30s %10s %10s\n", config, "raster", "raytrace");
        const auto row = [](const char* label, double a, double b, const char* note) {
            std::printf("  %-28s %10.3f %10.3f%s\n", label, ms3(a), ms3(b), note);
        };
        row("visibility ms", c.raster.visibility_ms, c.raytrace.visibility_ms, "   (tile rasterizer | primary rays)");
        row("shading ms", c.raster.shading_ms, c.raytrace.shading_ms, "");
        std::printf("  %-28s %10s %10.3f   (per frame: objects that moved)\n", "bvh ms", "-", ms3(c.raytrace.bvh_ms));
        row("frame ms", c.raster.frame_ms, c.raytrace.frame_ms, "");
        if (c.shadows)
            row("shadows ms", c.shadows->maps_ms, c.shadows->rays_ms, "   (shadow maps | shadow rays)");
        std::printf("  %-28s %10.1f %10.1f%s\n", "peak resident MiB", mib1(c.raster.peak_resident_mib),
                    mib1(c.raytrace.peak_resident_mib), r.peak_per_renderer ? "" : "   (the process's peak so far)");
        std::printf("  %-28s %10s %10.3f   (refit %.3f)\n", "bvh build ms", "", ms3(c.bvh.build_ms), ms3(c.bvh.refit_ms));
        std::printf("  %-28s %9.4f%%   of %zu pixels\n", "ids agree", percent(c.ids.fraction()), c.ids.pixels);
        if (!c.shadows && r.lights > 4)
            std::printf("  %-28s not compared: %zu lights, shadows are cast from at most 4\n", "shadows", r.lights);
        if (c.shadows)
            std::printf("  %-28s %9.4f%%   of %zu covered pixels; %.4f%% of %zu away from grazing light\n",
                        "shadows agree", percent(c.shadows->all.agreement()), c.shadows->all.compared,
                        percent(c.shadows->non_grazing.agreement()), c.shadows->non_grazing.compared);
    }
    if (r.sweep.empty()) return;
    const ConfigFigures& first = r.configs.front();
    std::printf("sweep at %dx%d, %d thread(s), copies of the content in a grid (raster | raytrace):\n",
                first.width, first.height, first.threads);
    for (const SweepPoint& p : r.sweep)
        std::printf("  %6d copies %12llu tris  frame ms %10.3f %10.3f   visibility ms %10.3f %10.3f\n", p.copies,
                    (unsigned long long)p.triangles, ms3(p.raster.frame_ms), ms3(p.raytrace.frame_ms),
                    ms3(p.raster.visibility_ms), ms3(p.raytrace.visibility_ms));
    const SweepPoint& last = r.sweep.back();
    print_crossover("frame ms", r.frame_crossover, r, last.raytrace.frame_ms < last.raster.frame_ms);
    print_crossover("visibility ms", r.visibility_crossover, r, last.raytrace.visibility_ms < last.raster.visibility_ms);
}

std::string report_json(const ComparisonReport& r) {
    nlohmann::json j;
    j["tessera_compare"] = 1;  // the schema's version
    j["command"] = r.command;
    j["date"] = r.date;
    j["machine"] = {{"cpu", r.cpu}, {"hardware_threads", r.hardware_threads}, {"simd", r.simd}};
    j["content"] = {{"source", r.content}, {"triangles", r.triangles}, {"lights", r.lights}};
    j["repeat"] = r.repeat;
    j["peak_resident_scope"] = r.peak_per_renderer ? "renderer" : "process";
    j["configurations"] = nlohmann::json::array();
    for (const ConfigFigures& c : r.configs) {
        nlohmann::json cj = {{"width", c.width},
                             {"height", c.height},
                             {"threads", c.threads},
                             {"raster", renderer_json(c.raster, false)},
                             {"raytrace", renderer_json(c.raytrace, true)},
                             {"bvh", {{"build_ms", ms3(c.bvh.build_ms)}, {"refit_ms", ms3(c.bvh.refit_ms)}}},
                             {"ids", {{"pixels", c.ids.pixels}, {"equal", c.ids.equal}, {"agree_percent", percent(c.ids.fraction())}}}};
        if (c.shadows)
            cj["shadows"] = {{"lights", c.shadows->lights},
                             {"maps_ms", ms3(c.shadows->maps_ms)},
                             {"rays_ms", ms3(c.shadows->rays_ms)},
                             {"all", agreement_json(c.shadows->all)},
                             {"non_grazing", agreement_json(c.shadows->non_grazing)}};
        else
            cj["shadows"] = nullptr;
        j["configurations"].push_back(std::move(cj));
    }
    j["sweep"] = nlohmann::json::array();
    for (const SweepPoint& p : r.sweep)
        j["sweep"].push_back({{"copies", p.copies},
                              {"triangles", p.triangles},
                              {"raster", renderer_json(p.raster, false)},
                              {"raytrace", renderer_json(p.raytrace, true)}});
    j["crossover"] = {{"frame", crossover_json(r.frame_crossover)}, {"visibility", crossover_json(r.visibility_crossover)}};
    return j.dump(2) + "\n";
}

}  // namespace tessera::cli
