#include "raster/shade/frame_shading.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "raster/pipeline/barycentrics.h"
#include "raster/shade/background_radiance.h"
#include "raster/shade/shade_kernel.h"

namespace tessera::shade {
namespace {

using shade::kLanes;
using shade::Lanes;

const texture::Texture* texture_of(const scene::Scene& scene, int32_t index) {
    return index == scene::kNoTexture ? nullptr : &scene.textures[size_t(index)];
}

// What fill_lanes broadcasts for a triangle besides its corners' attributes.
struct TriangleSetup {
    uint32_t triangle = kNoTriangle;
    float drawn = 0.0f;  // FrameShading::drawn_side
    pipeline::PerspectiveBarycentrics barycentrics;
};

// The kernel's colours to kLanes consecutive pixels, alpha 1 (an opaque surface covers its
// pixel whatever its material's opacity).
void put_opaque(glm::vec4* out, const Lanes& lanes) {
    using simd::vfloat;
    simd::store_interleaved4(&out->r, vfloat::load(lanes.out[0]), vfloat::load(lanes.out[1]), vfloat::load(lanes.out[2]),
                             vfloat(1.0f));
}

}  // namespace

// The set-ups of the triangles a tile shows, direct-mapped by the id's low bits: a triangle
// crosses several rows of a tile, and each row's groups would otherwise redo its set-up (three
// cross products in double precision) and drawn side. Valid for one FrameShading: start()
// empties it, at the start of each tile pass and shade() call.
struct FrameShading::TriangleSetups {
    static constexpr uint32_t kSlots = 1024;
    std::vector<TriangleSetup> slot = std::vector<TriangleSetup>(kSlots);
    std::vector<uint32_t> used;

    void start() {
        for (const uint32_t s : used) slot[s].triangle = kNoTriangle;
        used.clear();
    }
    const TriangleSetup& of(const FrameShading& shading, uint32_t triangle) {
        TriangleSetup& entry = slot[triangle & (kSlots - 1)];
        if (entry.triangle == triangle) return entry;
        if (entry.triangle == kNoTriangle) used.push_back(triangle & (kSlots - 1));
        const uint32_t* corner = &shading.baked_.mesh.indices[3 * size_t(triangle)];
        entry.triangle = triangle;
        entry.barycentrics = pipeline::PerspectiveBarycentrics::from_clip(
            shading.clip_[corner[0]], shading.clip_[corner[1]], shading.clip_[corner[2]], shading.state_.width,
            shading.state_.height);
        entry.drawn = shading.drawn_side(triangle);
        return entry;
    }
};

FrameShading::FrameShading(const scene::BakedScene& baked, const scene::Scene& scene, RenderState state)
    : baked_(baked), scene_(scene), state_(std::move(state)), eye_(state_.camera.eye) {
    if (state_.width <= 0 || state_.height <= 0)
        throw std::invalid_argument("shading needs a positive frame size");
    const Mesh& mesh = baked_.mesh;
    if (baked_.triangle_material.size() != mesh.triangle_count() ||
        baked_.vertex_material.size() != mesh.vertex_count())
        throw std::invalid_argument("shading: the baked scene's material ids do not match its mesh");
    for (uint32_t m : baked_.vertex_material)
        if (m >= scene_.materials.size())
            throw std::invalid_argument("shading: a vertex refers to material " + std::to_string(m) +
                                        ", but the scene has " + std::to_string(scene_.materials.size()));

    // Pixel rays: the inverse of V and P restricted to directions. A camera-space
    // direction (x_ndc / P00, y_ndc / P11, -1) goes to world space through the rows u, v, w
    // of the view matrix. The NDC are the whole frame's: a camera window (camera.h) maps the
    // window's NDC affinely onto them, which folds into the three vectors.
    const Camera& camera = state_.camera;
    const glm::mat4 view = camera.view();
    const glm::mat4 lens = camera.lens_projection();
    const glm::vec3 u(view[0][0], view[1][0], view[2][0]);
    const glm::vec3 v(view[0][1], view[1][1], view[2][1]);
    const glm::vec3 w(view[0][2], view[1][2], view[2][2]);
    ray_x_ = u / lens[0][0];
    ray_y_ = v / lens[1][1];
    ray_z_ = -w;
    if (!camera.window.whole()) {
        const glm::vec2 centre = camera.window.frame_ndc(glm::vec2(0.0f));
        ray_z_ += ray_x_ * centre.x + ray_y_ * centre.y;
        ray_x_ *= 0.5f * (camera.window.x_high - camera.window.x_low);
        ray_y_ *= 0.5f * (camera.window.y_high - camera.window.y_low);
    }

    const glm::mat4 vp = camera.projection() * view;
    clip_.resize(mesh.vertex_count());
    bool any_gouraud = false;
    for (const scene::Material& m : scene_.materials) any_gouraud |= m.model == scene::ShadingModel::gouraud;
    if (any_gouraud) gouraud_.assign(mesh.vertex_count(), glm::vec3(0.0f));

    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.vertex_count(), 8192),
                      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            const glm::vec4 c = vp * glm::vec4(mesh.positions[i], 1.0f);
            clip_[i] = c;
            if (!any_gouraud) continue;
            const scene::Material& m = scene_.materials[baked_.vertex_material[i]];
            if (m.model != scene::ShadingModel::gouraud) continue;
            // The per-vertex (Gouraud) shader: Blinn-Phong with the vertex normal.
            using V = simd::V3<float>;
            const glm::vec3 pw = mesh.positions[i];
            const V p{pw.x, pw.y, pw.z};
            const V to_eye = normalize_or(V{eye_.x, eye_.y, eye_.z} - p, V{0.0f, 0.0f, 1.0f});
            const glm::vec3 nw = mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[i];
            const V n = normalize_or(V{nw.x, nw.y, nw.z}, to_eye);
            const V c3 = shade::blinn_phong<float>(state_.lights, p, n, to_eye, shade::broadcast<float>(m.ka),
                                                   shade::broadcast<float>(m.kd),
                                                   shade::broadcast<float>(m.ks), m.shine);
            gouraud_[i] = {c3.x, c3.y, c3.z};
        }
    });
}

float FrameShading::drawn_side(uint32_t id) const {
    if (!state_.rasterized || id >= baked_.mesh.triangle_count()) return 0.0f;
    const uint32_t* corner = &baked_.mesh.indices[3 * size_t(id)];
    const pipeline::ClipVertices& v = *state_.rasterized;
    if (corner[0] >= v.size() || corner[1] >= v.size() || corner[2] >= v.size()) return 0.0f;
    const pipeline::ProjectedVertex &a = v.projected[corner[0]], &b = v.projected[corner[1]],
                                    &c = v.projected[corner[2]];
    if (a.code | b.code | c.code) return 0.0f;
    // Twice the signed area as triangle setup computes it (window y runs down: < 0 is
    // counter-clockwise in NDC, the front by winding).
    const int64_t area2 = int64_t(b.window.X - a.window.X) * (c.window.Y - a.window.Y) -
                          int64_t(b.window.Y - a.window.Y) * (c.window.X - a.window.X);
    if (area2 == 0) return 0.0f;  // not drawn
    const auto l1 = [](const pipeline::WindowVertex& p, const pipeline::WindowVertex& q) {
        return std::abs(int64_t(q.X) - p.X) + std::abs(int64_t(q.Y) - p.Y);
    };
    // First order: half a sub-pixel times the edges' |dX| + |dY| (exact edges, each within one
    // sub-pixel per axis of the snapped ones: + 3); second order: the cross product of two
    // moves of at most one sub-pixel per axis: + 2.
    const int64_t bound = (l1(a.window, b.window) + l1(b.window, c.window) + l1(c.window, a.window) + 6) / 2 + 2;
    if (std::abs(area2) > bound) return 0.0f;
    return area2 < 0 ? 1.0f : -1.0f;
}

bool FrameShading::transparent(uint32_t triangle) const {
    return triangle < baked_.triangle_material.size() &&
           scene_.materials[baked_.triangle_material[triangle]].transparent();
}

glm::vec4 FrameShading::background(int x, int y) const {
    const float xn = 2.0f * (float(x) + 0.5f) / float(state_.width) - 1.0f;
    const float yn = 1.0f - 2.0f * (float(y) + 0.5f) / float(state_.height);
    return glm::vec4(background_radiance(scene_.background, ray_x_ * xn + ray_y_ * yn + ray_z_), 1.0f);
}

simd::V3<simd::vfloat> FrameShading::background_lanes(int x0, int y) const {
    using simd::vfloat;
    // background()'s arithmetic, in its order, with x_ndc per lane.
    const vfloat x = simd::to_float(simd::vint(x0) + simd::lane_index());
    const vfloat xn = vfloat(2.0f) * (x + vfloat(0.5f)) / vfloat(float(state_.width)) - vfloat(1.0f);
    const float yn = 1.0f - 2.0f * (float(y) + 0.5f) / float(state_.height);
    const glm::vec3 row = ray_y_ * yn;
    const simd::V3<vfloat> d{(vfloat(ray_x_.x) * xn + vfloat(row.x)) + vfloat(ray_z_.x),
                             (vfloat(ray_x_.y) * xn + vfloat(row.y)) + vfloat(ray_z_.y),
                             (vfloat(ray_x_.z) * xn + vfloat(row.z)) + vfloat(ray_z_.z)};
    return background_radiance_lanes(scene_.background, d);
}

template <class F>
void FrameShading::shade_with(std::span<const CoveredPixel> pixels, std::span<glm::vec4> out) const {
    if (out.size() != pixels.size())
        throw std::invalid_argument("shade: one output per fragment is needed");
    const Mesh& mesh = baked_.mesh;
    const size_t material_count = scene_.materials.size();

    // Group by material, keeping the pixels' order within a group (counting sort); the
    // last bucket collects pixels without a valid triangle.
    // Neighbouring pixels mostly share a material: counted by runs, a tile of one material
    // costs no increment per pixel, and needs no sort.
    // The runs are kept and placed whole, so no pass increments a counter per pixel.
    struct Run {
        uint32_t bucket, begin, end;
    };
    thread_local std::vector<uint32_t> count, order, next;
    thread_local std::vector<Run> runs;
    count.assign(material_count + 2, 0);
    runs.clear();
    const auto bucket = [&](const CoveredPixel& f) {
        return f.triangle < baked_.triangle_material.size() ? size_t(baked_.triangle_material[f.triangle])
                                                            : material_count;
    };
    size_t buckets_used = 0;
    for (size_t i = 0; i < pixels.size();) {
        const size_t b = bucket(pixels[i]);
        size_t end = i + 1;
        while (end < pixels.size() && bucket(pixels[end]) == b) ++end;
        buckets_used += count[b + 1] == 0;
        count[b + 1] += uint32_t(end - i);
        runs.push_back({uint32_t(b), uint32_t(i), uint32_t(end)});
        i = end;
    }
    for (size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    order.resize(pixels.size());
    if (buckets_used <= 1) {
        for (size_t i = 0; i < pixels.size(); ++i) order[i] = uint32_t(i);
    } else {
        next.assign(count.begin(), count.end() - 1);
        for (const Run& r : runs) {
            uint32_t* to = order.data() + next[r.bucket];
            for (uint32_t i = r.begin; i < r.end; ++i) *to++ = i;
            next[r.bucket] += r.end - r.begin;
        }
    }
    for (size_t i = count[material_count]; i < pixels.size(); ++i)
        out[order[i]] = background(pixels[order[i]].x, pixels[order[i]].y);

    shade::KernelContext ctx;
    ctx.lights = state_.lights;
    ctx.eye = eye_;
    Lanes lanes;
    uint32_t whole = kNoTriangle;  // see fill_lanes
    thread_local TriangleSetups setups;
    setups.start();
    for (size_t mat = 0; mat < material_count; ++mat) {
        const scene::Material& material = scene_.materials[mat];
        ctx.material = &material;
        ctx.diffuse = texture_of(scene_, material.diffuse_texture);
        ctx.normal = material.model == scene::ShadingModel::gouraud ? nullptr : texture_of(scene_, material.normal_texture);
        const bool needs_uv = ctx.diffuse || ctx.normal;
        const bool needs_colour = material.model == scene::ShadingModel::gouraud;
        for (size_t start = count[mat]; start < count[mat + 1]; start += kLanes) {
            const int n = int(std::min<size_t>(kLanes, count[mat + 1] - start));
            uint32_t setup_for = kNoTriangle;  // consecutive pixels often share a triangle
            pipeline::PerspectiveBarycentrics setup{};
            if constexpr (!std::is_same_v<F, float>) {
                CoveredPixel lane_pixel[kLanes];
                for (int lane = 0; lane < kLanes; ++lane) lane_pixel[lane] = pixels[order[start + size_t(lane < n ? lane : 0)]];
                fill_lanes(lane_pixel, needs_uv, needs_colour, lanes, whole, setups);
                shade::shade_lanes<F>(ctx, lanes, 0);
                for (int l = 0; l < n; ++l)
                    out[order[start + size_t(l)]] = {lanes.out[0][l], lanes.out[1][l], lanes.out[2][l], lanes.out[3][l]};
                continue;
            }
            float drawn = 0.0f;
            for (int lane = 0; lane < kLanes; ++lane) {
                // Idle lanes repeat the first pixel so every lane computes finite values.
                const CoveredPixel& f = pixels[order[start + size_t(lane < n ? lane : 0)]];
                const uint32_t* corner = &mesh.indices[3 * size_t(f.triangle)];
                if (f.triangle != setup_for) {
                    setup = pipeline::PerspectiveBarycentrics::from_clip(clip_[corner[0]], clip_[corner[1]],
                                                               clip_[corner[2]], state_.width, state_.height);
                    drawn = drawn_side(f.triangle);
                    setup_for = f.triangle;
                }
                lanes.drawn[lane] = drawn;
                lanes.x[lane] = float(f.x) + 0.5f;
                lanes.y[lane] = float(f.y) + 0.5f;
                for (int k = 0; k < 3; ++k) {
                    const uint32_t vi = corner[k];
                    const glm::vec3 p = mesh.positions[vi];
                    const glm::vec3 nrm = mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[vi];
                    for (int a = 0; a < 3; ++a) {
                        lanes.bary[k][a][lane] = setup.e[k][a];
                        lanes.pos[k][a][lane] = p[a];
                        lanes.nrm[k][a][lane] = nrm[a];
                    }
                    // Only what the material reads: the gathers dominate the kernel's cost.
                    if (needs_uv) {
                        const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[vi];
                        lanes.uv[k][0][lane] = uv.x;
                        lanes.uv[k][1][lane] = uv.y;
                    }
                    if (needs_colour)
                        for (int a = 0; a < 3; ++a) lanes.col[k][a][lane] = gouraud_[vi][a];
                }
            }
            if constexpr (std::is_same_v<F, float>) {
                for (int lane = 0; lane < n; ++lane) shade::shade_lanes<float>(ctx, lanes, lane);
            } else {
                shade::shade_lanes<F>(ctx, lanes, 0);
            }
            for (int lane = 0; lane < n; ++lane)
                out[order[start + size_t(lane)]] = {lanes.out[0][lane], lanes.out[1][lane], lanes.out[2][lane],
                                                    lanes.out[3][lane]};
        }
    }
}

void FrameShading::fill_lanes(const CoveredPixel* lane_pixel, bool needs_uv, bool needs_colour, Lanes& lanes,
                              uint32_t& whole, TriangleSetups& setups) const {
    // The lanes in runs of one triangle (all of them, on triangles wider than the lanes): each
    // run's corner attributes are broadcast to its lanes with a masked vector store per
    // attribute instead of being written lane by lane; the values are the lane-by-lane path's.
    using F = simd::vfloat;
    const Mesh& mesh = baked_.mesh;
    // The pixel centres, float(x) + 0.5 and float(y) + 0.5, in lanes: the three int32 fields of
    // the pixels deinterleaved by one load each.
    static_assert(sizeof(CoveredPixel) == 3 * sizeof(int32_t), "x, y, triangle: three packed int32");
    simd::vint column, row, triangles;
    simd::load_interleaved3(&lane_pixel[0].x, column, row, triangles);
    (simd::to_float(column) + F(0.5f)).store(lanes.x);
    (simd::to_float(row) + F(0.5f)).store(lanes.y);
    // A triangle wider than the lanes covers group after group: its corner attributes, the
    // side it was drawn from and the barycentric set-up (with its divisions) are already in
    // every lane from the group before, so only the pixel centres change. The triangle decides the material, hence
    // needs_uv and needs_colour, so what the lanes hold is what a fill would write.
    if (whole != kNoTriangle && simd::all(triangles == simd::vint(int32_t(whole)))) return;
    whole = kNoTriangle;
    int lane = 0;
    while (lane < kLanes) {
        const uint32_t triangle = lane_pixel[lane].triangle;
        const int first = lane;
        while (lane < kLanes && lane_pixel[lane].triangle == triangle) ++lane;
        const simd::vint index = simd::lane_index();
        const simd::vmask run = (simd::vint(first) < index + simd::vint(1)) & (index < simd::vint(lane));
        const bool whole_run = first == 0 && lane == kLanes;
        const auto fill = [&](float* lanes_of, float v) {
            if (whole_run) F(v).store(lanes_of);
            else simd::store_masked(lanes_of, run, F(v));
        };
        const uint32_t* corner = &mesh.indices[3 * size_t(triangle)];
        const TriangleSetup& setup = setups.of(*this, triangle);
        fill(lanes.drawn, setup.drawn);
        for (int k = 0; k < 3; ++k) {
            const uint32_t vi = corner[k];
            const glm::vec3 p = mesh.positions[vi];
            const glm::vec3 nrm = mesh.normals.empty() ? glm::vec3(0.0f) : mesh.normals[vi];
            for (int a = 0; a < 3; ++a) {
                fill(lanes.bary[k][a], setup.barycentrics.e[k][a]);
                fill(lanes.pos[k][a], p[a]);
                fill(lanes.nrm[k][a], nrm[a]);
            }
            if (needs_uv) {
                const glm::vec2 uv = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[vi];
                fill(lanes.uv[k][0], uv.x);
                fill(lanes.uv[k][1], uv.y);
            }
            if (needs_colour)
                for (int a = 0; a < 3; ++a) fill(lanes.col[k][a], gouraud_[vi][a]);
        }
        if (whole_run) whole = triangle;
    }
}

void FrameShading::shade_tile_surfaces(const Tile& tile) const {
    const size_t material_count = scene_.materials.size();
    const std::vector<uint32_t>& triangle_material = baked_.triangle_material;
    // Per thread, kept from tile to tile: the pixels left for shade().
    thread_local std::vector<CoveredPixel> rest;
    thread_local std::vector<glm::vec4> rest_colours;
    rest.clear();
    shade::KernelContext ctx;
    ctx.lights = state_.lights;
    ctx.eye = eye_;
    size_t ctx_for = material_count;
    bool needs_uv = false, needs_colour = false;
    Lanes lanes;
    uint32_t whole = kNoTriangle;  // see fill_lanes
    thread_local TriangleSetups setups;
    setups.start();
    CoveredPixel lane_pixel[kLanes];
    // Triangle ids at or above this have no material (kNoTriangle included: negative as int32).
    const int32_t material_limit = int32_t(std::min<size_t>(triangle_material.size(), size_t(INT32_MAX)));
    const float* material_table = reinterpret_cast<const float*>(triangle_material.data());
    for (int y = tile.rect.y0; y < tile.rect.y1; ++y)
        for (int x0 = tile.rect.x0; x0 < tile.rect.x1; x0 += kLanes) {
            const int n = std::min(kLanes, tile.rect.x1 - x0);
            // The covered pixels of the group and whether they show one material.
            uint32_t covered = 0;
            size_t material = material_count;
            bool one_material = true;
            uint32_t previous = kNoTriangle;
            if (n == kLanes && material_limit > 0) {
                // A whole group: the same decisions in lanes (covered ids, their materials by a
                // gather; one material when every covered lane has the first covered lane's),
                // instead of a branch per pixel. A layer's pixels it does not hold
                // (Tile::coverage 0) count as uncovered.
                alignas(64) int32_t ids[kLanes], mats[kLanes];
                const int32_t* row = reinterpret_cast<const int32_t*>(&tile.triangle_at(x0, y));
                if (tile.coverage) {
                    const uint8_t* held = &tile.coverage[tile.offset(x0, y)];
                    for (int i = 0; i < kLanes; ++i) ids[i] = held[i] ? row[i] : int32_t(kNoTriangle);
                    row = ids;
                }
                const simd::vint id = simd::vint::load_unaligned(row);
                const simd::vmask on = simd::andnot(id == simd::vint(int32_t(kNoTriangle)), simd::vmask(true));
                covered = simd::bits(on);
                if (covered == 0) continue;
                if (whole != kNoTriangle && simd::all(id == simd::vint(int32_t(whole)))) {
                    // The whole group shows the triangle whose attributes fill the lanes
                    // (fill_lanes' `whole`, of the material in ctx): only the centres change.
                    (simd::to_float(simd::vint(x0) + simd::lane_index()) + simd::vfloat(0.5f)).store(lanes.x);
                    simd::vfloat(float(y) + 0.5f).store(lanes.y);
                    shade::shade_lanes<simd::vfloat>(ctx, lanes, 0);
                    put_opaque(&tile.colour_at(x0, y), lanes);
                    continue;
                }
                const simd::vmask known = on & (id >= simd::vint(0)) & (id < simd::vint(material_limit));
                const simd::vint looked = simd::bits_of(simd::gather(material_table, simd::select(known, id, simd::vint(0))));
                const simd::vint m = simd::select(known, looked, simd::vint(int32_t(material_count)));
                id.store(ids);
                m.store(mats);
                const int lead = std::countr_zero(covered);
                material = size_t(uint32_t(mats[lead]));  // material_count when unknown
                one_material = material < material_count &&
                               (simd::bits(on & (m == simd::vint(mats[lead]))) == covered);
                for (int i = 0; i < kLanes; ++i) lane_pixel[i] = {x0 + i, y, uint32_t(ids[i])};
            } else for (int i = 0; i < n; ++i) {
                const int x = x0 + i;
                if (!tile.active(x, y)) continue;
                const uint32_t id = tile.triangle_at(x, y);
                if (id == kNoTriangle) continue;
                covered |= 1u << i;
                lane_pixel[i] = {x, y, id};
                if (id == previous) continue;
                previous = id;
                const size_t m = id < triangle_material.size() ? size_t(triangle_material[id]) : material_count;
                if (material == material_count && m < material_count && (covered & ((1u << i) - 1)) == 0) material = m;
                one_material &= m == material;
            }
            if (covered == 0) continue;
            if (!one_material || material == material_count) {
                for (uint32_t c = covered; c; c &= c - 1) rest.push_back(lane_pixel[std::countr_zero(c)]);
                continue;
            }
            // Idle lanes repeat the first covered pixel (shade()'s rule: finite values).
            const CoveredPixel& first = lane_pixel[std::countr_zero(covered)];
            for (int i = 0; i < kLanes; ++i)
                if (i >= n || !(covered >> i & 1u)) lane_pixel[i] = first;
            if (material != ctx_for) {
                const scene::Material& m = scene_.materials[material];
                ctx.material = &m;
                ctx.diffuse = texture_of(scene_, m.diffuse_texture);
                ctx.normal = m.model == scene::ShadingModel::gouraud ? nullptr : texture_of(scene_, m.normal_texture);
                needs_uv = ctx.diffuse || ctx.normal;
                needs_colour = m.model == scene::ShadingModel::gouraud;
                ctx_for = material;
            }
            fill_lanes(lane_pixel, needs_uv, needs_colour, lanes, whole, setups);
            shade::shade_lanes<simd::vfloat>(ctx, lanes, 0);
            // Opaque surfaces cover the pixel whatever their material's opacity.
            glm::vec4* out = &tile.colour_at(x0, y);
            if (covered == simd::kEveryLaneBits) {
                put_opaque(out, lanes);
                continue;
            }
            for (uint32_t c = covered; c; c &= c - 1) {
                const int i = std::countr_zero(c);
                out[i] = glm::vec4(lanes.out[0][i], lanes.out[1][i], lanes.out[2][i], 1.0f);
            }
        }
    if (rest.empty()) return;
    rest_colours.resize(rest.size());
    shade(rest, rest_colours);
    for (size_t i = 0; i < rest.size(); ++i)
        tile.colour_at(rest[i].x, rest[i].y) = glm::vec4(glm::vec3(rest_colours[i]), 1.0f);
}

void FrameShading::shade(std::span<const CoveredPixel> pixels, std::span<glm::vec4> out) const {
    shade_with<simd::vfloat>(pixels, out);
}

void FrameShading::shade_reference(std::span<const CoveredPixel> pixels, std::span<glm::vec4> out) const {
    shade_with<float>(pixels, out);
}

void shade_tile(const FrameShading& shading, const Tile& tile) {
    shade_surfaces(shading, tile);
    shade_background(shading, tile);
}

void shade_background(const FrameShading& shading, const Tile& tile) {
    const auto one = [&](int x, int y) { return tile.active(x, y) && tile.triangle_at(x, y) == kNoTriangle; };
    const auto whole = [&](int x0, int y) {
        uint32_t mask = 0;
        if (tile.coverage) {  // a layer's pixels it does not hold are left alone
            for (int i = 0; i < kLanes; ++i) mask |= uint32_t(one(x0 + i, y)) << i;
            return mask;
        }
        const simd::vint id = simd::vint::load_unaligned(reinterpret_cast<const int32_t*>(&tile.triangle_at(x0, y)));
        return simd::bits(id == simd::vint(int32_t(kNoTriangle)));
    };
    fill_background_lanes(
        tile, [&](int x0, int y, int n) { return empty_mask(x0, y, n, whole, one); },
        [&](int x0, int y) { return shading.background_lanes(x0, y); });
}

void shade_background_reference(const FrameShading& shading, const Tile& tile) {
    for (int y = tile.rect.y0; y < tile.rect.y1; ++y)
        for (int x = tile.rect.x0; x < tile.rect.x1; ++x)
            if (tile.active(x, y) && tile.triangle_at(x, y) == kNoTriangle) tile.colour_at(x, y) = shading.background(x, y);
}

void shade_surfaces(const FrameShading& shading, const Tile& tile) { shading.shade_tile_surfaces(tile); }

void shade_surfaces_reference(const FrameShading& shading, const Tile& tile) {
    std::vector<CoveredPixel> pixels;
    std::vector<glm::vec4> colours;
    pixels.reserve(size_t(tile.width()) * size_t(tile.height()));
    for (int y = tile.rect.y0; y < tile.rect.y1; ++y)
        for (int x = tile.rect.x0; x < tile.rect.x1; ++x) {
            if (!tile.active(x, y)) continue;
            const uint32_t id = tile.triangle_at(x, y);
            if (id != kNoTriangle) pixels.push_back({x, y, id});
        }
    colours.resize(pixels.size());
    shading.shade(pixels, colours);
    for (size_t i = 0; i < pixels.size(); ++i) {
        const CoveredPixel& f = pixels[i];
        // Opaque surfaces cover the pixel whatever their material's opacity (transparent
        // triangles never reach the visibility buffer; a ray caster's might).
        tile.colour_at(f.x, f.y) = glm::vec4(glm::vec3(colours[i]), 1.0f);
    }
}

void blend_fragments(const FrameShading& shading, std::span<const CoveredPixel> pixels, const Tile& tile) {
    std::vector<glm::vec4> colours(pixels.size());
    shading.shade(pixels, colours);
    for (size_t i = 0; i < pixels.size(); ++i) {
        glm::vec4& dst = tile.colour_at(pixels[i].x, pixels[i].y);
        dst = blend_over(dst, colours[i]);
    }
}

Frame shade_visibility(const FrameShading& shading, VisibilityBuffer& visibility) {
    const RenderState& s = shading.state();
    if (visibility.width != s.width || visibility.height != s.height)
        throw std::invalid_argument("shade_visibility: the visibility buffer is " +
                                    std::to_string(visibility.width) + "x" + std::to_string(visibility.height) +
                                    ", the frame " + std::to_string(s.width) + "x" + std::to_string(s.height));
    Frame frame(s.width, s.height);
    parallel_for_tiles(TileGrid(s.width, s.height, 64), [&](int, const TileRect& rect) {
        shade_tile(shading, frame_tile(visibility, frame.pixels.data(), rect));
    });
    return frame;
}

}  // namespace tessera::shade
