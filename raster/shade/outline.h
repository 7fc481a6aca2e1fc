// Ink outlines of toon surfaces, one pixel wide whatever the surface's size on screen.
//
// The toon shader inks where |N.V| < 0.2, a band whose width on screen shrinks with the
// surface's curvature radius: on a thin body (the toon scene's snake, 10 pixels across) it is
// a fraction of a pixel and the outline breaks into dashes. This pass finds the silhouette in
// the visibility buffer instead, as edge detection on depth does in NPR renderers: a covered
// pixel of a toon material is inked when, along a row or a column, a neighbour is background,
// shows another material farther away (a body resting on the floor is outlined where the two
// meet, though the floor there is barely farther), or is farther with a crease in depth (a
// body in front of itself).
//
// The crease test works on w = 1/d (d the distance along the view axis), which is affine in
// screen space across any plane (so is window depth; w is it rescaled to be relative): on a
// plane w(a) + w(b) - 2 w(p) = 0 for the neighbours a, b of p on either side, however steep
// the plane, so a floor seen at a grazing angle is never inked. At a silhouette the farther
// neighbour breaks the line; the step and the crease are measured relative to w(p), so the
// threshold is the same at every distance.
#pragma once
#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/visibility.h"
#include "raster/scene/material.h"

namespace tessera::shade {

// Relative step in 1/distance that counts as an edge: 1% (a body 4 units away standing more
// than 4 cm in front of what is behind it).
inline constexpr float kOutlineStep = 0.01f;

// Blackens the outline pixels of `colour` (linear RGBA, visibility's size, rows top to
// bottom) in rows [row_begin, row_end); `triangle_material` maps triangle ids to `materials`.
// Only toon materials are outlined. Reads neighbours in rows row_begin - 1 .. row_end: the
// result of a row does not depend on how the rows are split, so any thread count and any
// split into bands give the same bytes. Rows in parallel, each through OutlinePass.
void draw_outlines(const VisibilityBuffer& visibility, const Camera& camera,
                   std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials,
                   std::vector<glm::vec4>& colour, int row_begin, int row_end);
// The same, pixel by pixel on one thread, every neighbour's 1/distance computed where it is
// read: the definition OutlinePass is tested against.
void draw_outlines_reference(const VisibilityBuffer& visibility, const Camera& camera,
                             std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials,
                             std::vector<glm::vec4>& colour, int row_begin, int row_end);

// draw_outlines for a caller that splits (and times) the rows itself. Per row it computes
// once what each pixel's tests read of its neighbours (1/distance, material, background), so
// a pixel costs a few comparisons instead of five double-precision divisions and four
// material lookups; the decisions are draw_outlines_reference's, bit for bit.
class OutlinePass {
public:
    OutlinePass(const VisibilityBuffer& visibility, const Camera& camera,
                std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials);
    // Whether some material is toon (else run() does nothing).
    bool active() const { return active_; }
    // Rows [row_begin, row_end) of `colour` (clamped to the frame), on the calling thread.
    void run(std::vector<glm::vec4>& colour, int row_begin, int row_end) const;
    // The same on a frame already encoded as 8-bit RGBA (4 bytes a pixel, visibility's size):
    // an inked pixel's colour bytes become 0 (what black encodes to), its alpha byte stays.
    void run(uint8_t* rgba8, int row_begin, int row_end) const;

private:
    template <class Ink>
    void run_rows(const Ink& ink, int row_begin, int row_end) const;

    const VisibilityBuffer& visibility_;
    double near_, far_;
    std::span<const uint32_t> triangle_material_;
    std::vector<int32_t> toon_;  // per material: 1 toon, 0 not
    bool active_ = false;
};

// True when some material is toon (the pass has work).
bool any_outlined(std::span<const scene::Material> materials);

}  // namespace tessera::shade
