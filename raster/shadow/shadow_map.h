// Shadow maps rendered by tessera's own rasterizer (Williams 1978: draw the
// scene from the light, keep the depth), then looked up per surface point with a bias and
// percentage-closer filtering.
//
// The light is a point light; its map is one perspective view from the light towards the
// centre of the mesh's bounding sphere, with the field of view and near/far planes fitted to
// that sphere, so every triangle of the frame lies inside the map (a light inside the sphere
// gets a 120-degree view: points outside it count as lit; a cube map would be the cure).
//
// Bias, in texels of the map at the receiver's distance (so it follows the resolution and
// the distance to the light): the receiver is pushed `normal_offset * sin(theta)` texels
// along its normal (theta: angle between normal and light) and `depth_bias` texels towards
// the light before it is projected. Why sin(theta): a tap D texels away from the receiver
// reads a plane whose depth differs by D * texel * tan(theta) along the light, and a point
// h above the plane is h / cos(theta) in front of it, so h >= D * texel * sin(theta) keeps
// every tap in front. The farthest 3x3 PCF tap is D = sqrt(2) + 0.71 = 2.12 texels away
// (the receiver can sit anywhere in its texel), hence the default 2.5: no acne on flat
// surfaces at any angle, and almost no offset (no light leaking) where the light is steep.
// `depth_bias` covers the depth buffer's rounding.
//
// PCF: (2r+1)^2 nearest-texel depth comparisons around the receiver; lit_fraction() is the
// fraction passing, and lit() their majority (the binary state the light mask keeps).
// mark_lit() answers lit() for a whole tile of surface points, simd::kLanes at a time, with
// the same float operations in the same order (receiver_in_map in shadow_map.cpp), so it
// equals mark_lit_reference(), the one-point-at-a-time definition, bit for bit.
//
// The map is rendered depth only (RasterOptions::depth_only): no triangle ids are written.
#pragma once
#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "raster/core/mesh.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/light_mask.h"
#include "raster/core/visibility.h"

namespace tessera::shadow {

struct ShadowMapOptions {
    int resolution = 2048;       // square map, 16 .. kMaxViewport texels
    float normal_offset = 2.5f;  // texels times sin(theta), along the surface normal
    float depth_bias = 0.5f;     // texels, towards the light
    int pcf_radius = 1;          // (2r+1)^2 taps; 0: a single tap
};

class ShadowMap {
public:
    // Renders the depth of `mesh` as seen from `light`. Throws std::invalid_argument for a
    // resolution outside 16 .. kMaxViewport, a PCF radius outside 0 .. 8 or a negative bias.
    ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& light,
              const ShadowMapOptions& options = {});

    // Renders again (the next frame: the mesh or light moved), reusing the map's memory.
    void render(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& light);

    // Fraction of the PCF taps that see `position` (pushed off the surface along `normal`)
    // from the light.
    float lit_fraction(const glm::vec3& position, const glm::vec3& normal) const;
    // Whether at least half the taps see it (stops reading taps once the answer is known).
    bool lit(const glm::vec3& position, const glm::vec3& normal) const;

    // Sets `bit` in visible[i] for every point i that faces the light (faces_light) and is
    // lit(): SIMD over the points. visible.size() must be points.size().
    void mark_lit(const SurfacePoints& points, uint8_t bit, std::span<uint8_t> visible) const;
    // The same, one point at a time through faces_light() and lit() (the reference).
    void mark_lit_reference(const SurfacePoints& points, uint8_t bit, std::span<uint8_t> visible) const;

    const glm::vec3& light() const { return light_; }
    const glm::mat4& view_projection() const { return view_projection_; }
    // The map's window depths, resolution x resolution texels, rows top to bottom.
    std::span<const float> depth() const { return depth_.depth; }
    const ShadowMapOptions& options() const { return options_; }

private:
    // Counts lit taps; with kMajority, stops once at least half are lit or more than half
    // are not, returning a count on the right side of half.
    template <bool kMajority>
    int count_lit(const glm::vec3& position, const glm::vec3& normal) const;

    glm::vec3 light_;
    ShadowMapOptions options_;
    glm::mat4 view_projection_;
    glm::vec3 axis_;            // unit view direction of the light
    float texel_per_depth_;     // texel size in world units per unit of view depth
    VisibilityBuffer depth_;
};

// A LightTest looking up maps[l] for lights[l] (the maps must be rendered for those lights).
LightTest shadow_map_test(std::span<const ShadowMap> maps);

}  // namespace tessera::shadow
