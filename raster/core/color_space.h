// The one place where tessera converts between linear radiance and display encodings.
//
// Rendering and blending happen in linear light (float RGBA). Display files (PNG, TIFF) store
// sRGB-encoded values, EXR stores the linear floats unchanged. Colour textures read from 8-bit
// files are sRGB-encoded and are decoded to linear before they are filtered; data textures
// (normal maps, height maps) are used as stored.
//
// The transfer function is IEC 61966-2-1 (sRGB), applied to R, G and B; alpha is linear
// coverage and never encoded:
//     encode(c) = 12.92 c                     for c <= 0.0031308
//               = 1.055 c^(1/2.4) - 0.055     otherwise
//     decode(e) = e / 12.92                   for e <= 0.04045
//               = ((e + 0.055) / 1.055)^2.4   otherwise
#pragma once

namespace tessera {

// Linear [0, 1] -> sRGB-encoded [0, 1]. Values outside [0, 1] are clamped; NaN gives 0.
float linear_to_srgb(float linear);
// sRGB-encoded [0, 1] -> linear [0, 1] (clamped the same way).
float srgb_to_linear(float encoded);

}  // namespace tessera
