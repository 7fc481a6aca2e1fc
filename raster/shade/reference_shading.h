// The fixed shaders of `tessera raster --shade` (id, depth, normal, phong). "phong" is defined
// to the letter in issue 3 so that other renderers (Mesa llvmpipe through a GLSL shader equal
// to it) can render the same image and be compared pixel by pixel:
//
//   per pixel, two-sided (N flipped when dot(N, V) < 0), OBJ normals and uv interpolated
//   perspective-correctly (face normals / uv (0,0) when missing); with d = |lookat - eye|,
//   fwd = (lookat - eye)/d, right = normalize(fwd x up), up' = right x fwd, a point light at
//   eye + right*0.4d + up'*0.5d + fwd*0.2d; L, V to the light and the eye, H = normalize(L+V);
//   albedo = mix((0.80,0.35,0.20), (0.90,0.85,0.70), checker),
//   checker = mod(floor(u*16) + floor(v*8), 2);
//   colour = albedo*(0.08 + 0.92*max(N.L, 0)) + 0.5*max(N.H, 0)^48,
//   clamped to [0, 1] and quantised to 8 bits as round(c*255), no sRGB encoding.
//
// Background (no triangle): black. id: a hash colour per triangle id; depth: grey = window
// depth (the command shows depth_view.h's mapping of the visible distances instead);
// normal: N*0.5 + 0.5 (interpolated or face normal, not flipped).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "raster/pipeline/barycentrics.h"
#include "raster/core/camera.h"
#include "raster/core/mesh.h"
#include "raster/pipeline/tile_pass.h"
#include "raster/core/visibility.h"

namespace tessera::shade {

enum class ShadeMode { id, depth, normal, phong };

// Parses "id" | "depth" | "normal" | "phong"; throws std::invalid_argument otherwise.
ShadeMode parse_shade_mode(const std::string& text);

// A tile pass that shades every pixel of the tile into ctx.colour (linear RGBA, alpha 1; skipped
// when the rasterizer gives no colour tile) and into `rgba8` (width*height pixels, rows top to
// bottom, sized by the caller; each pixel pack_rgba8 of its 8-bit channels). The scalar
// definition that the SIMD pass (stamp_shading.h) is tested against. It reads the frame's
// visibility (RasterOptions::frame_visibility true).
pipeline::TilePass make_reference_shading_pass(ShadeMode mode, const Camera& camera, std::vector<uint32_t>& rgba8);

// What both shading passes share, so that they read the same inputs bit for bit.

// The eye and the point light of --shade phong for `camera`.
struct PhongLight {
    glm::vec3 eye{0.0f}, light{0.0f};
    static PhongLight from(const Camera& camera);
};

// Everything per triangle that a pixel needs: its barycentrics and its vertex attributes.
struct TriangleAttributes {
    uint32_t id = kNoTriangle;
    pipeline::PerspectiveBarycentrics barycentrics;
    glm::vec3 position[3]{};
    glm::vec3 normal[3]{};  // the face normal three times when the mesh has none
    glm::vec2 uv[3]{};      // (0, 0) when the mesh has none
};
void fetch_triangle_attributes(const pipeline::TileContext& ctx, uint32_t id, TriangleAttributes& t);

// --shade id: the colour of a triangle id, 8 bits per channel.
uint32_t id_colour(uint32_t id);

// An opaque 8-bit RGBA pixel as one word: red in the low byte, alpha 255 in the high one (the
// byte order R, G, B, A in memory on little-endian machines).
inline uint32_t pack_rgba8(uint8_t r, uint8_t g, uint8_t b) {
    return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | 0xFF000000u;
}

// The 8-bit RGB bytes of an RGBA8 frame (what image files of --out-color hold).
std::vector<uint8_t> rgb8_of(const std::vector<uint32_t>& rgba8);

// round(clamp(c, 0, 1) * 255) as floor(x * 255 + 0.5).
inline uint8_t quantise(float c) {
    return uint8_t(std::floor(std::min(std::max(c, 0.0f), 1.0f) * 255.0f + 0.5f));
}

}  // namespace tessera::shade
