#include "raster/shadow/mask_compare.h"

#include <stdexcept>
#include <vector>

#include "raster/io/image_io.h"

namespace tessera::shadow {
namespace {

void check_sizes(const LightMask& a, const LightMask& b, const VisibilityBuffer& visibility,
                 const LightMask* exclude) {
    const auto same = [&](const LightMask& m) {
        return m.width == visibility.width && m.height == visibility.height &&
               m.bits.size() == visibility.triangle.size();
    };
    if (!same(a) || !same(b) || (exclude && !same(*exclude)))
        throw std::invalid_argument("light masks to compare differ in size from the frame");
}

}  // namespace

MaskAgreement compare_light_masks(const LightMask& a, const LightMask& b,
                                  const VisibilityBuffer& visibility, const LightMask* exclude) {
    check_sizes(a, b, visibility, exclude);
    MaskAgreement result;
    for (size_t p = 0; p < visibility.triangle.size(); ++p) {
        if (visibility.triangle[p] == kNoTriangle) continue;
        if (exclude && exclude->bits[p]) {
            ++result.excluded;
            continue;
        }
        ++result.compared;
        const uint8_t only_a = a.bits[p] & ~b.bits[p], only_b = b.bits[p] & ~a.bits[p];
        result.differ += (only_a | only_b) != 0;
        result.only_a_lit += only_a != 0;
        result.only_b_lit += only_b != 0;
    }
    return result;
}

LightTest grazing_lights(float max_cosine) {
    return [max_cosine](const SurfacePoints& points, std::span<const glm::vec3> lights,
                        std::span<uint8_t> visible) {
        for (size_t i = 0; i < points.size(); ++i)
            for (size_t l = 0; l < lights.size(); ++l) {
                const glm::vec3 to_light = lights[l] - points.position[i];
                const float cosine = glm::dot(points.normal[i], to_light) / glm::length(to_light);
                if (cosine > 0.0f && cosine < max_cosine) visible[i] |= uint8_t(1u << l);
            }
    };
}

void write_mask_diff(const std::filesystem::path& path, const LightMask& a, const LightMask& b,
                     const VisibilityBuffer& visibility, const LightMask* exclude) {
    check_sizes(a, b, visibility, exclude);
    std::vector<uint8_t> rgb(visibility.triangle.size() * 3, 0);
    for (size_t p = 0; p < visibility.triangle.size(); ++p) {
        uint8_t* out = &rgb[3 * p];
        if (visibility.triangle[p] == kNoTriangle) continue;
        const bool a_more = (a.bits[p] & ~b.bits[p]) != 0, b_more = (b.bits[p] & ~a.bits[p]) != 0;
        if (exclude && exclude->bits[p]) {
            out[0] = out[1] = 110;
        } else if (a_more || b_more) {
            out[0] = a_more ? 255 : 0;
            out[2] = b_more ? 255 : 0;
        } else {
            out[0] = out[1] = out[2] = a.bits[p] ? 235 : 90;
        }
    }
    io::write_image(path, io::ImageView{visibility.width, visibility.height, 3, io::PixelType::u8, rgb.data(), /*srgb=*/true});
}

}  // namespace tessera::shadow
