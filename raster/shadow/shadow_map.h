// Shadow maps rendered by tessera's own rasterizer (Williams 1978: draw the scene from the
// light, keep the depth), then looked up per surface point with a bias and
// percentage-closer filtering.
//
// Where the maps look (shadow/cascades.h): given the camera, a light gets
// ShadowMapSettings::cascades maps split along the camera's view, each fitted to its slice
// of the view frustum (orthographic and texel-snapped for a distant light, perspective for a
// point light); without a camera, one map covers the mesh's bounding sphere. A receiver
// reads the first cascade that holds it with all its PCF taps (cascades are ordered from
// the camera outwards, so that is the finest one that can answer); a receiver outside every
// cascade counts as lit.
//
// Bias, in texels of the cascade read at the receiver (so it follows each cascade's
// resolution and, for a point light, the distance to the light): the receiver is pushed
// `normal_offset * sin(theta)` texels along its normal (theta: angle between normal and
// light) and `depth_bias` texels towards the light before it is projected (normal-offset
// bias). Why sin(theta): a tap D texels away from the receiver reads a plane whose depth
// differs by D * texel * tan(theta) along the light, and a point h above the plane is
// h / cos(theta) in front of it, so h >= D * texel * sin(theta) keeps every tap in front.
// lit() is the majority of the 3x3 PCF taps, so only the 5 nearest must be in front: the
// 5th nearest tap centre is at most sqrt(1.5^2 + 0.5^2) = 1.58 texels away (receiver at a
// texel corner), hence the default 1.6: no acne on flat surfaces at any angle, and almost
// no offset where the light is steep. (Every tap in front would take 2.12 texels, which
// visibly shrinks shadows at their edges.) Because the offset is in texels and the near
// cascades' texels are small (millimetres on a room-sized view), the offset stays far below
// the size of an object resting on a surface: contact shadows survive. `depth_bias` covers
// the depth buffer's rounding.
//
// PCF: a (2r+1)^2 box of nearest-texel depth comparisons around the receiver's texel;
// lit_fraction() is the fraction passing, and lit() their majority (the binary state the
// light mask keeps). mark_lit() answers lit() for a whole tile of surface points,
// simd::kLanes at a time, with the same float operations in the same order
// (receiver_in_map in shadow_map.cpp), so it equals mark_lit_reference(), the
// one-point-at-a-time definition, bit for bit.
//
// The maps are rendered depth only (RasterOptions::depth_only): no triangle ids are written.
// An orthographic cascade is handed only the triangles that can reach its window (not all
// three vertices beyond one of its edges): the near cascades see a small part of the
// scene, and the rasterizer's per-triangle work is most of a map's cost.
#pragma once
#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/mesh.h"
#include "raster/core/shadow_map_settings.h"
#include "raster/core/visibility.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/cascades.h"
#include "raster/shadow/light_mask.h"

namespace tessera::shadow {

using ShadowMapOptions = ShadowMapSettings;

// Where shadows are cast from: a point light's position, or for a distant (directional)
// light a point far along its direction (the point shadow rays aim at) with `distant` set,
// which makes the maps orthographic along that direction.
struct ShadowLight {
    glm::vec3 position{0.0f};
    bool distant = false;
    ShadowLight(const glm::vec3& p, bool d = false) : position(p), distant(d) {}  // NOLINT: a point light converts
};

class ShadowMap {
public:
    // One map over the whole mesh (options.cascades is not used). Throws
    // std::invalid_argument for settings out of range (check_shadow_map_settings).
    ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const ShadowLight& light,
              const ShadowMapOptions& options = {});
    ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& point_light,
              const ShadowMapOptions& options = {})
        : ShadowMap(rasterizer, mesh, ShadowLight(point_light), options) {}
    // options.cascades maps fitted to what `camera` sees.
    ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const ShadowLight& light,
              const Camera& camera, const ShadowMapOptions& options);

    // Renders again (the next frame: the mesh, light or camera moved), reusing the maps'
    // memory; `camera` null: one map over the whole mesh. A cascade whose projection is the
    // same as last time and in whose window no triangle moved keeps its depth (it would
    // render to the same bytes): in an animation only the maps a light, the camera's fit or
    // a caster changed are drawn again.
    void render(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const ShadowLight& light,
                const Camera* camera = nullptr);
    // How many cascades the last render() drew (the others were kept).
    int cascades_rendered() const { return cascades_rendered_; }

    // Fraction of the PCF taps that see `position` (pushed off the surface along `normal`)
    // from the light, in the cascade that holds it (1 outside every cascade).
    float lit_fraction(const glm::vec3& position, const glm::vec3& normal) const;
    // Whether at least half the taps see it (stops reading taps once the answer is known).
    bool lit(const glm::vec3& position, const glm::vec3& normal) const;
    // The cascade lit() reads for this receiver; cascade_count() when none holds it.
    int cascade_of(const glm::vec3& position, const glm::vec3& normal) const;

    // Sets `bit` in visible[i] for every point i that faces the light (faces_light) and is
    // lit(): SIMD over the points. visible.size() must be points.size().
    void mark_lit(const SurfacePoints& points, uint8_t bit, std::span<uint8_t> visible) const;
    // The same, one point at a time through faces_light() and lit() (the reference).
    void mark_lit_reference(const SurfacePoints& points, uint8_t bit, std::span<uint8_t> visible) const;

    const glm::vec3& light() const { return light_.position; }
    int cascade_count() const { return int(cascades_.size()); }
    const LightProjection& projection(int cascade = 0) const { return cascades_[size_t(cascade)].projection; }
    const glm::mat4& view_projection(int cascade = 0) const { return projection(cascade).view_projection; }
    // View depths of the camera where each cascade starts and ends (cascade_count() + 1
    // values); empty for a map over the whole mesh.
    const std::vector<float>& splits() const { return splits_; }
    // A cascade's window depths, resolution x resolution texels, rows top to bottom.
    std::span<const float> depth(int cascade = 0) const { return cascades_[size_t(cascade)].depth.depth; }
    const ShadowMapOptions& options() const { return options_; }

private:
    struct Cascade {
        LightProjection projection;
        VisibilityBuffer depth;
        bool rendered = false;  // depth holds `projection`'s view of the mesh last rendered
    };

    // Whether cascade c, whose projection did not change, must be drawn again because some
    // triangle reaching its window (before or after) moved; `moved`: per vertex.
    bool moved_in_window(const Mesh& mesh, const LightProjection& projection, bool orthographic,
                         const std::vector<uint8_t>& moved) const;

    // The cascade holding the receiver and the taps of it that are lit; with kMajority,
    // stops once at least half are lit or more than half are not, returning a count on the
    // right side of half.
    template <bool kMajority>
    int count_lit(const glm::vec3& position, const glm::vec3& normal, int* cascade = nullptr) const;

    ShadowLight light_;
    ShadowMapOptions options_;
    Mesh culled_;  // for an orthographic cascade: the triangles that reach its window
    Mesh rendered_mesh_;  // the mesh of the last render, to find what moved since
    std::vector<uint8_t> moved_;  // per vertex: its position changed since the last render
    int cascades_rendered_ = 0;
    std::vector<float> splits_;
    std::vector<Cascade> cascades_;
};

// A LightTest looking up maps[l] for lights[l] (the maps must be rendered for those lights).
LightTest shadow_map_test(std::span<const ShadowMap> maps);

}  // namespace tessera::shadow
