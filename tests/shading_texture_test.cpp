// Textures: mip chains for any size, filters, wrap modes and the mip level from derivatives.
#include <gtest/gtest.h>

#include <filesystem>

#include "raster/error.h"
#include "raster/texture/sampler.h"
#include "raster/texture/texture.h"

using namespace tessera;

namespace {

// A one-texel checkerboard: the worst case for minification (every level >= 1 is grey).
Texture checker(int w, int h, int cell = 1) {
    std::vector<glm::vec4> t(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t[size_t(y * w + x)] = glm::vec4(glm::vec3(float(((x / cell) + (y / cell)) & 1)), 1.0f);
    return Texture(w, h, std::move(t));
}

glm::vec4 mean(const MipLevel& level) {
    glm::vec4 sum(0.0f);
    for (const glm::vec4& t : level.texels) sum += t;
    return sum / float(level.texels.size());
}

}  // namespace

TEST(ShadingTexture, MipChainHandlesNonPowerOfTwoAndOneByOne) {
    const Texture t = checker(5, 3);
    ASSERT_EQ(t.level_count(), 3);  // 5x3, 2x1, 1x1
    EXPECT_EQ(t.level(1).width, 2);
    EXPECT_EQ(t.level(1).height, 1);
    EXPECT_EQ(t.level(2).width, 1);
    // The box weights keep the mean on every level (no texel of the odd row/column dropped).
    for (int k = 1; k < t.level_count(); ++k) EXPECT_NEAR(mean(t.level(k)).r, mean(t.level(0)).r, 1e-6f) << k;

    const Texture one(1, 1, {glm::vec4(0.2f, 0.4f, 0.6f, 1.0f)});
    EXPECT_EQ(one.level_count(), 1);
    for (TextureFilter f : {TextureFilter::nearest, TextureFilter::bilinear, TextureFilter::mipmap, TextureFilter::trilinear})
        EXPECT_EQ(sample(one, {0.7f, -3.2f}, {{10.0f, 0}, {0, 10.0f}}, f, TextureWrap::repeat).g, 0.4f);
    EXPECT_THROW(Texture(0, 4, {}), std::invalid_argument);
    EXPECT_THROW(Texture(2, 2, {glm::vec4(1.0f)}), std::invalid_argument);
}

TEST(ShadingTexture, FiltersAndWrapModes) {
    std::vector<glm::vec4> texels = {glm::vec4(0.0f), glm::vec4(1.0f), glm::vec4(0.0f), glm::vec4(1.0f)};
    const Texture t(2, 2, texels);  // columns 0 and 1
    const UvDerivatives none;
    // Texel centres give the texel exactly; halfway between centres gives the average.
    EXPECT_EQ(sample(t, {0.25f, 0.25f}, none, TextureFilter::bilinear, TextureWrap::clamp).r, 0.0f);
    EXPECT_EQ(sample(t, {0.75f, 0.25f}, none, TextureFilter::bilinear, TextureWrap::clamp).r, 1.0f);
    EXPECT_FLOAT_EQ(sample(t, {0.5f, 0.25f}, none, TextureFilter::bilinear, TextureWrap::clamp).r, 0.5f);
    // Left of the first centre: clamp keeps texel 0, repeat blends with the last column.
    EXPECT_EQ(sample(t, {0.0f, 0.25f}, none, TextureFilter::bilinear, TextureWrap::clamp).r, 0.0f);
    EXPECT_FLOAT_EQ(sample(t, {0.0f, 0.25f}, none, TextureFilter::bilinear, TextureWrap::repeat).r, 0.5f);
    EXPECT_EQ(sample(t, {1.75f, 0.25f}, none, TextureFilter::nearest, TextureWrap::repeat).r, 1.0f);
    EXPECT_EQ(sample(t, {1.75f, 0.25f}, none, TextureFilter::nearest, TextureWrap::clamp).r, 1.0f);
    EXPECT_EQ(sample(t, {-0.25f, 0.25f}, none, TextureFilter::nearest, TextureWrap::repeat).r, 1.0f);
    // Non-finite coordinates do not crash.
    EXPECT_TRUE(std::isfinite(sample(t, {NAN, INFINITY}, none, TextureFilter::trilinear, TextureWrap::repeat).r));
}

TEST(ShadingTexture, MipLevelFollowsTheDerivatives) {
    const Texture t = checker(256, 256);
    // One pixel step covers 4 texels: lambda = log2(4) = 2; level 2 of a 1-texel checker is grey.
    const UvDerivatives four{{4.0f / 256.0f, 0.0f}, {0.0f, 4.0f / 256.0f}};
    EXPECT_FLOAT_EQ(mip_lambda(t, four), 2.0f);
    EXPECT_FLOAT_EQ(sample(t, {0.3f, 0.6f}, four, TextureFilter::trilinear, TextureWrap::repeat).r, 0.5f);
    EXPECT_FLOAT_EQ(sample(t, {0.3f, 0.6f}, four, TextureFilter::mipmap, TextureWrap::repeat).r, 0.5f);
    // Without mip-mapping the same footprint aliases to black or white.
    const float aliased = sample(t, {0.3f, 0.6f}, four, TextureFilter::nearest, TextureWrap::repeat).r;
    EXPECT_TRUE(aliased == 0.0f || aliased == 1.0f);
    // The larger of the two axes decides (anisotropic footprint), and magnification is level 0.
    EXPECT_FLOAT_EQ(mip_lambda(t, {{1.0f / 256.0f, 0.0f}, {0.0f, 16.0f / 256.0f}}), 4.0f);
    EXPECT_LT(mip_lambda(t, {{0.1f / 256.0f, 0.0f}, {0.0f, 0.1f / 256.0f}}), 0.0f);
    // Between levels trilinear blends: lambda = 0.5 gives half level 0, half level 1.
    const Texture ramp(2, 1, {glm::vec4(0.0f), glm::vec4(1.0f)});
    const UvDerivatives half_step{{std::sqrt(2.0f) / 2.0f, 0.0f}, {0.0f, 0.0f}};
    EXPECT_NEAR(mip_lambda(ramp, half_step), 0.5f, 1e-6f);
    EXPECT_NEAR(sample(ramp, {0.25f, 0.5f}, half_step, TextureFilter::trilinear, TextureWrap::clamp).r, 0.25f, 1e-6f);
}

TEST(ShadingTexture, LoadingFlipsRowsDecodesSrgbAndReportsMissingFiles) {
    FloatImage img;
    img.width = 1;
    img.height = 2;
    img.channels = 3;
    img.pixels = {1.0f, 1.0f, 1.0f, 0.5f, 0.5f, 0.5f};  // top row white, bottom row 0.5
    const Texture linear = Texture::from_image(img, TexelEncoding::linear);
    EXPECT_EQ(linear.level(0).at(0, 0).r, 0.5f);  // row 0 = v = 0 = the bottom of the file
    EXPECT_EQ(linear.level(0).at(0, 1).r, 1.0f);
    const Texture srgb = Texture::from_image(img, TexelEncoding::srgb);
    EXPECT_NEAR(srgb.level(0).at(0, 0).r, 0.21404f, 1e-4f);
    EXPECT_THROW(load_texture("/nonexistent/texture.png", TexelEncoding::srgb), Error);
}
