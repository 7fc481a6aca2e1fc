#include "procedural/rd_presets.h"

#include <array>

namespace tessera::procedural {

namespace {
// Sources: Karl Sims' tutorial (default, mitosis, coral); pmneila/jsexp grayscott.js (mazes,
// solitons, chaos, spots-and-loops); Pearson (1993) class theta as set up in GollyGang Ready;
// "worms" is in Pearson's class kappa region (Munafo's map). jsexp's own worms (0.078, 0.061)
// and waves (0.014, 0.045) die out from these seeds under Sims' scheme, so they are not here.
// "spots" and "stripes" are the two pattern classes the tests check by blob counting.
constexpr std::array kPresets{
    RdPreset{"spots", 0.0367f, 0.0649f, "isolated round spots that divide until they fill the plane (Sims' mitosis)"},
    RdPreset{"stripes", 0.029f, 0.057f, "long winding stripes, a labyrinth (jsexp mazes)"},
    RdPreset{"default", 0.055f, 0.062f, "Karl Sims' first image: spreading maze-like fingers"},
    RdPreset{"mitosis", 0.0367f, 0.0649f, "Sims' mitosis: spots that grow and split"},
    RdPreset{"coral", 0.0545f, 0.062f, "Sims' coral growth: branching fingers"},
    RdPreset{"worms", 0.054f, 0.063f, "worms and loops (Pearson class kappa)"},
    RdPreset{"mazes", 0.029f, 0.057f, "labyrinth of stripes (jsexp)"},
    RdPreset{"solitons", 0.03f, 0.062f, "stable isolated spots (jsexp)"},
    RdPreset{"holes", 0.039f, 0.058f, "a sheet pierced by round holes (negative spots)"},
    RdPreset{"chaos", 0.026f, 0.051f, "turbulent, never settling (jsexp)"},
    RdPreset{"loops", 0.018f, 0.051f, "spots and loops (jsexp)"},
    RdPreset{"theta", 0.040f, 0.060f, "Pearson's class theta (Ready's Pearson1993 set-up)"},
};
}  // namespace

std::span<const RdPreset> rd_presets() { return kPresets; }

const RdPreset* find_rd_preset(std::string_view name) {
    for (const RdPreset& p : kPresets)
        if (p.name == name) return &p;
    return nullptr;
}

std::string rd_preset_names() {
    std::string names;
    for (const RdPreset& p : kPresets) {
        if (!names.empty()) names += ", ";
        names += p.name;
    }
    return names;
}

}  // namespace tessera::procedural
