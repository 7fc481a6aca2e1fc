// The procedural/ fields as marchable surfaces, each with the two planes that enclose it
// (entered and left between planes y = 0 and y = 1):
// - terrain f = h(p.xz) - p.y: h lies in [base, base + amplitude] (dunes add their ripple
//   amplitude on top);
// - the 16-sine noise f = w/32 + 0.5 - p.y with |w| <= 16: the surface lies in
//   [0, 1] (a hair more for the approximated sines);
// - the value-noise volume f = base + amplitude * fbm - p.y with |fbm| <= 1;
// - the gradient-noise surface f = base + amplitude * n - p.y, |n| "about 1": 10 % margin.
#pragma once
#include "procedural/field.h"
#include "raster/march/gradient_noise_field.h"
#include "raster/march/march_surface.h"

namespace tessera::march {

inline SlabSurface<procedural::TerrainField> terrain_surface(const procedural::TerrainField& field) {
    const procedural::TerrainParams& p = field.params();
    const float ripple = p.relief == procedural::Relief::dunes ? p.amplitude * p.dunes.ripple_amplitude : 0.0f;
    return {field, Slab{p.base - ripple, p.base + p.amplitude + ripple}};
}

inline SlabSurface<procedural::SineNoiseField> sine_noise_surface(const procedural::SineNoiseField& field) {
    return {field, Slab{0.0f, 1.001f}};
}

inline SlabSurface<procedural::NoiseVolumeField> noise_volume_surface(const procedural::NoiseVolumeField& field) {
    const procedural::VolumeParams& p = field.params();
    return {field, Slab{p.base - p.amplitude, p.base + p.amplitude}};
}

inline SlabSurface<GradientNoiseField> gradient_noise_surface(const GradientNoiseField& field) {
    return {field, Slab{field.base - 1.1f * field.amplitude, field.base + 1.1f * field.amplitude}};
}

}  // namespace tessera::march
