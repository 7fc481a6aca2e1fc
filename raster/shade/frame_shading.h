// Shading of a frame: turns "which triangle covers this pixel" into linear RGBA, reading only
// the visibility (triangle id per pixel or per fragment), the frame's baked world-space mesh
// and the scene's materials, textures and lights. It does not care how visibility was found:
// the tile rasterizer and the Embree ray caster feed it the same way.
//
// Per pixel it computes the perspective-correct barycentrics of the covering triangle at the
// pixel centre from its clip-space corners (barycentrics.h: 2D homogeneous rasterization,
// the textbook "interpolate u/h, v/h, 1/h, then divide" in closed form), and their screen-space
// derivatives analytically from the same plane equations, which select the mip level.
// Attributes are interpolated with b, then the material's model shades (lighting.h).
//
// The work is SIMD over pixels: they are grouped by material (counting sort, stable),
// and each group is shaded kLanes at a time with simd::vfloat; the same template kernel
// instantiated with float is the scalar reference path (shade_reference).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/frame.h"
#include "raster/core/tile.h"
#include "raster/scene/scene.h"
#include "raster/simd/lane_math.h"
#include "raster/core/visibility.h"
#include "raster/pipeline/vertex_stage.h"

namespace tessera::shade {

// RenderState: what every shader of the frame reads, passed by value.
struct RenderState {
    Camera camera;
    int width = 0;   // pixels
    int height = 0;
    std::vector<scene::Light> lights;
    // The tile rasterizer's vertices when it finds the visibility (the raster renderer; its
    // vertex stage fills them before the tile passes shade): a triangle whose side its
    // snapped vertices decide is lit from the side it was drawn from (FrameShading::drawn_side()).
    // Null for ray-cast visibility: the side the geometry faces the eye with.
    const pipeline::ClipVertices* rasterized = nullptr;
};

// One covered pixel to shade: pixel (x, y), rows top to bottom, and the id of the triangle
// seen there in the baked mesh.
struct CoveredPixel {
    int32_t x = 0;
    int32_t y = 0;
    uint32_t triangle = 0;
};

class FrameShading {
public:
    // Precomputes the per-vertex work of the frame in parallel: clip-space corners and the
    // Gouraud colours of vertices whose material is Gouraud. `baked` and `scene` must outlive
    // this object. Throws std::invalid_argument for a non-positive size or a bake that does
    // not match the scene's materials.
    FrameShading(const scene::BakedScene& baked, const scene::Scene& scene, RenderState state);

    // Linear RGBA of each pixel (alpha = material opacity x diffuse texture alpha), in any
    // mix of triangles and materials; out.size() must equal pixels.size(). A pixel
    // whose triangle id is out of range gets the background.
    void shade(std::span<const CoveredPixel> pixels, std::span<glm::vec4> out) const;
    // The same through the scalar instantiation of the kernel, one pixel at a time.
    void shade_reference(std::span<const CoveredPixel> pixels, std::span<glm::vec4> out) const;

    // The environment seen through pixel (x, y), alpha 1.
    glm::vec4 background(int x, int y) const;
    // Its RGB through pixels (x0 + i, y), one per lane i < kLanes: background() lane by lane.
    simd::V3<simd::vfloat> background_lanes(int x0, int y) const;

    const RenderState& state() const { return state_; }
    bool transparent(uint32_t triangle) const;

    // The opaque surfaces of a tile (shade_surfaces): kLanes pixels of a row at a time where
    // they show one material (the kernel's lanes filled straight from the row, the colours
    // written back in place), the rest through shade(). Each pixel's colour is shade()'s.
    void shade_tile_surfaces(const Tile& tile) const;

    // The side from which the rasterizer (RenderState::rasterized) drew triangle `id`, where
    // snapping may have decided it: +1 for counter-clockwise in NDC (the front by winding), -1
    // for clockwise; 0 where the projected triangle is wide enough that the snapped winding is
    // the projected one, which the geometry's own test gives (and for clipped triangles, whose
    // pieces keep the polygon's winding). Snapping moves each vertex by at most half a
    // sub-pixel per axis, which changes twice the signed area by at most half the sum of
    // |dX| + |dY| over the edges plus a few sub-pixels^2: a sliver thinner than that seen
    // nearly edge-on can come out of the snap turned over, front for back. Lit by the world
    // geometry it would show its other side (at a ridge seen from above, the underside: an
    // unlit speck where the rasterizer drew the front layer).
    float drawn_side(uint32_t id) const;

private:
    template <class F>
    void shade_with(std::span<const CoveredPixel> pixels, std::span<glm::vec4> out) const;
    // Fills `lanes` for the kLanes pixels lane_pixel[0 .. kLanes) (one material; idle lanes
    // repeat a pixel of the group), in runs of one triangle. `whole`: the triangle whose
    // attributes fill every lane of `lanes` (kNoTriangle: none), kept by the caller from one
    // group to the next; a group all of that triangle only gets its pixel centres written.
    // `setups` holds the barycentric set-ups and drawn sides already computed for this object
    // (TriangleSetups, frame_shading.cpp).
    struct TriangleSetups;
    void fill_lanes(const CoveredPixel* lane_pixel, bool needs_uv, bool needs_colour, struct Lanes& lanes,
                    uint32_t& whole, TriangleSetups& setups) const;

    const scene::BakedScene& baked_;
    const scene::Scene& scene_;
    RenderState state_;
    glm::vec3 eye_;
    glm::vec3 ray_x_, ray_y_, ray_z_;   // pixel ray = ray_x * x_ndc + ray_y * y_ndc + ray_z
    std::vector<glm::vec4> clip_;       // clip-space position per vertex
    std::vector<glm::vec3> gouraud_;    // per vertex; empty when no material is Gouraud
};

// The opaque pass of a tile: visible pixels shaded, the others given the background (pixels
// the tile does not hold, Tile::coverage, are left alone). It is shade_surfaces then
// shade_background, which write disjoint pixels (callers time them apart). shade_background
// evaluates the environment kLanes pixels of a row at a time; shade_background_reference,
// one pixel at a time through background(), is what it is tested against.
void shade_tile(const FrameShading& shading, const Tile& tile);
void shade_surfaces(const FrameShading& shading, const Tile& tile);
// shade_surfaces as a list of the tile's covered pixels through FrameShading::shade(): what
// the row-wise pass is tested against.
void shade_surfaces_reference(const FrameShading& shading, const Tile& tile);
void shade_background(const FrameShading& shading, const Tile& tile);
void shade_background_reference(const FrameShading& shading, const Tile& tile);

// Alpha blending (glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA)) for the colour, c = c_src
// * a_src + c_dst * (1 - a_src). Coverage composes as "over", a = a_src + a_dst * (1 - a_src)
// (glBlendFuncSeparate's usual alpha factors), so a pixel that was opaque stays opaque;
// blending alpha like colour, a_src^2 + a_dst (1 - a_src) would leave frames partly transparent
// wherever glass was drawn.
inline glm::vec4 blend_over(glm::vec4 dst, glm::vec4 src) {
    return {glm::vec3(src) * src.a + glm::vec3(dst) * (1.0f - src.a), src.a + dst.a * (1.0f - src.a)};
}

// The transparent pass of a tile: `pixels` (inside the tile, already depth-tested
// against the opaque pass) are shaded together, then blended one after another in the given
// order — submission order — so the result is the same whatever the tiling and threads.
void blend_fragments(const FrameShading& shading, std::span<const CoveredPixel> pixels,
                     const Tile& tile);

// The opaque pass over a whole visibility buffer, tiles in parallel: how a renderer that
// produces a VisibilityBuffer (the Embree ray caster, the tests) gets its picture.
Frame shade_visibility(const FrameShading& shading, VisibilityBuffer& visibility);

}  // namespace tessera::shade
