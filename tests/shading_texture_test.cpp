// Textures: mip chains for any size, filters, wrap modes and the mip level from derivatives.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "raster/core/error.h"
#include "raster/texture/sampler.h"
#include "raster/texture/sampler_simd.h"
#include "raster/texture/texture.h"

using namespace tessera;

namespace {

// A one-texel checkerboard: the worst case for minification (every level >= 1 is grey).
texture::Texture checker(int w, int h, int cell = 1) {
    std::vector<glm::vec4> t(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t[size_t(y * w + x)] = glm::vec4(glm::vec3(float(((x / cell) + (y / cell)) & 1)), 1.0f);
    return texture::Texture(w, h, std::move(t));
}

glm::vec4 mean(const texture::MipLevel& level) {
    glm::vec4 sum(0.0f);
    for (const glm::vec4& t : level.texels) sum += t;
    return sum / float(level.texels.size());
}

}  // namespace

TEST(ShadingTexture, MipChainHandlesNonPowerOfTwoAndOneByOne) {
    const texture::Texture t = checker(5, 3);
    ASSERT_EQ(t.level_count(), 3);  // 5x3, 2x1, 1x1
    EXPECT_EQ(t.level(1).width, 2);
    EXPECT_EQ(t.level(1).height, 1);
    EXPECT_EQ(t.level(2).width, 1);
    // The box weights keep the mean on every level (no texel of the odd row/column dropped).
    for (int k = 1; k < t.level_count(); ++k) EXPECT_NEAR(mean(t.level(k)).r, mean(t.level(0)).r, 1e-6f) << k;

    const texture::Texture one(1, 1, {glm::vec4(0.2f, 0.4f, 0.6f, 1.0f)});
    EXPECT_EQ(one.level_count(), 1);
    for (texture::TextureFilter f : {texture::TextureFilter::nearest, texture::TextureFilter::bilinear, texture::TextureFilter::mipmap, texture::TextureFilter::trilinear})
        EXPECT_FLOAT_EQ(texture::sample(one, {0.7f, -3.2f}, {{10.0f, 0}, {0, 10.0f}}, f, texture::TextureWrap::repeat).g, 0.4f);
    EXPECT_THROW(texture::Texture(0, 4, {}), std::invalid_argument);
    EXPECT_THROW(texture::Texture(2, 2, {glm::vec4(1.0f)}), std::invalid_argument);
}

TEST(ShadingTexture, FiltersAndWrapModes) {
    std::vector<glm::vec4> texels = {glm::vec4(0.0f), glm::vec4(1.0f), glm::vec4(0.0f), glm::vec4(1.0f)};
    const texture::Texture t(2, 2, texels);  // columns 0 and 1
    const texture::UvDerivatives none;
    // Texel centres give the texel exactly; halfway between centres gives the average.
    EXPECT_EQ(texture::sample(t, {0.25f, 0.25f}, none, texture::TextureFilter::bilinear, texture::TextureWrap::clamp).r, 0.0f);
    EXPECT_EQ(texture::sample(t, {0.75f, 0.25f}, none, texture::TextureFilter::bilinear, texture::TextureWrap::clamp).r, 1.0f);
    EXPECT_FLOAT_EQ(texture::sample(t, {0.5f, 0.25f}, none, texture::TextureFilter::bilinear, texture::TextureWrap::clamp).r, 0.5f);
    // Left of the first centre: clamp keeps texel 0, repeat blends with the last column.
    EXPECT_EQ(texture::sample(t, {0.0f, 0.25f}, none, texture::TextureFilter::bilinear, texture::TextureWrap::clamp).r, 0.0f);
    EXPECT_FLOAT_EQ(texture::sample(t, {0.0f, 0.25f}, none, texture::TextureFilter::bilinear, texture::TextureWrap::repeat).r, 0.5f);
    EXPECT_EQ(texture::sample(t, {1.75f, 0.25f}, none, texture::TextureFilter::nearest, texture::TextureWrap::repeat).r, 1.0f);
    EXPECT_EQ(texture::sample(t, {1.75f, 0.25f}, none, texture::TextureFilter::nearest, texture::TextureWrap::clamp).r, 1.0f);
    EXPECT_EQ(texture::sample(t, {-0.25f, 0.25f}, none, texture::TextureFilter::nearest, texture::TextureWrap::repeat).r, 1.0f);
    // Non-finite coordinates do not crash.
    EXPECT_TRUE(std::isfinite(texture::sample(t, {NAN, INFINITY}, none, texture::TextureFilter::trilinear, texture::TextureWrap::repeat).r));
}

TEST(ShadingTexture, MipLevelFollowsTheDerivatives) {
    const texture::Texture t = checker(256, 256);
    // One pixel step covers 4 texels: lambda = log2(4) = 2; level 2 of a 1-texel checker is grey.
    const texture::UvDerivatives four{{4.0f / 256.0f, 0.0f}, {0.0f, 4.0f / 256.0f}};
    EXPECT_FLOAT_EQ(texture::mip_lambda(t, four), 2.0f);
    EXPECT_FLOAT_EQ(texture::sample(t, {0.3f, 0.6f}, four, texture::TextureFilter::trilinear, texture::TextureWrap::repeat).r, 0.5f);
    EXPECT_FLOAT_EQ(texture::sample(t, {0.3f, 0.6f}, four, texture::TextureFilter::mipmap, texture::TextureWrap::repeat).r, 0.5f);
    // Without mip-mapping the same footprint aliases to black or white.
    const float aliased = texture::sample(t, {0.3f, 0.6f}, four, texture::TextureFilter::nearest, texture::TextureWrap::repeat).r;
    EXPECT_TRUE(aliased == 0.0f || aliased == 1.0f);
    // The larger of the two axes decides (anisotropic footprint), and magnification is level 0.
    EXPECT_FLOAT_EQ(texture::mip_lambda(t, {{1.0f / 256.0f, 0.0f}, {0.0f, 16.0f / 256.0f}}), 4.0f);
    EXPECT_LT(texture::mip_lambda(t, {{0.1f / 256.0f, 0.0f}, {0.0f, 0.1f / 256.0f}}), 0.0f);
    // Between levels trilinear blends: lambda = 0.5 gives half level 0, half level 1.
    const texture::Texture ramp(2, 1, {glm::vec4(0.0f), glm::vec4(1.0f)});
    const texture::UvDerivatives half_step{{std::sqrt(2.0f) / 2.0f, 0.0f}, {0.0f, 0.0f}};
    EXPECT_NEAR(texture::mip_lambda(ramp, half_step), 0.5f, 1e-6f);
    EXPECT_NEAR(texture::sample(ramp, {0.25f, 0.5f}, half_step, texture::TextureFilter::trilinear, texture::TextureWrap::clamp).r, 0.25f, 1e-6f);
}

TEST(ShadingTexture, LoadingFlipsRowsDecodesSrgbAndReportsMissingFiles) {
    io::FloatImage img;
    img.width = 1;
    img.height = 2;
    img.channels = 3;
    img.pixels = {1.0f, 1.0f, 1.0f, 0.5f, 0.5f, 0.5f};  // top row white, bottom row 0.5
    const texture::Texture linear = texture::Texture::from_image(img, texture::TexelEncoding::linear);
    EXPECT_EQ(linear.level(0).at(0, 0).r, 0.5f);  // row 0 = v = 0 = the bottom of the file
    EXPECT_EQ(linear.level(0).at(0, 1).r, 1.0f);
    const texture::Texture srgb = texture::Texture::from_image(img, texture::TexelEncoding::srgb);
    EXPECT_NEAR(srgb.level(0).at(0, 0).r, 0.21404f, 1e-4f);
    EXPECT_THROW(texture::load_texture("/nonexistent/texture.png", texture::TexelEncoding::srgb), Error);
}

TEST(ShadingTexture, SimdSamplerMatchesTheScalarSampler) {
    // A non-power-of-two texture with distinct texels; random coordinates (some far outside
    // [0, 1], some not finite) and footprints spanning every level, each lane on its own level.
    std::vector<glm::vec4> texels(37 * 23);
    for (size_t i = 0; i < texels.size(); ++i)
        texels[i] = glm::vec4(float(i % 37) / 37.0f, float(i / 37) / 23.0f, float((i * 7) % 11) / 11.0f, 1.0f - float(i % 5) / 10.0f);
    const texture::Texture t(37, 23, texels);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f), exponent(-8.0f, 4.0f);
    constexpr int L = simd::kLanes;
    float worst = 0.0f;
    for (texture::TextureFilter filter : {texture::TextureFilter::nearest, texture::TextureFilter::bilinear, texture::TextureFilter::mipmap, texture::TextureFilter::trilinear})
        for (texture::TextureWrap wrap : {texture::TextureWrap::repeat, texture::TextureWrap::clamp})
            for (int round = 0; round < 200; ++round) {
                alignas(64) float u[L], v[L], d[4][L], out[4][L];
                for (int i = 0; i < L; ++i) {
                    u[i] = coordinate(rng);
                    v[i] = coordinate(rng);
                    for (int k = 0; k < 4; ++k) d[k][i] = std::exp2(exponent(rng)) * (k == 1 || k == 2 ? 0.3f : 1.0f);
                }
                if (round == 0) {
                    u[0] = NAN;
                    v[0] = INFINITY;
                    d[0][0] = NAN;
                }
                using simd::vfloat;
                const texture::TexelLanes s = texture::sample_lanes(t, vfloat::load(u), vfloat::load(v), vfloat::load(d[0]),
                                                                vfloat::load(d[1]), vfloat::load(d[2]), vfloat::load(d[3]),
                                                                filter, wrap);
                s.r.store(out[0]);
                s.g.store(out[1]);
                s.b.store(out[2]);
                s.a.store(out[3]);
                for (int i = 0; i < L; ++i) {
                    const glm::vec4 ref = texture::sample(t, {u[i], v[i]}, {{d[0][i], d[1][i]}, {d[2][i], d[3][i]}}, filter, wrap);
                    for (int c = 0; c < 4; ++c) {
                        if (std::abs(out[c][i] - ref[c]) > 2e-5f && worst <= 2e-5f)
                            ADD_FAILURE() << "filter " << int(filter) << " wrap " << int(wrap) << " uv " << u[i] << "," << v[i]
                                          << " d " << d[0][i] << " " << d[1][i] << " " << d[2][i] << " " << d[3][i]
                                          << " channel " << c << ": " << out[c][i] << " vs " << ref[c];
                        worst = std::max(worst, std::abs(out[c][i] - ref[c]));
                    }
                }
            }
    EXPECT_LT(worst, 2e-5f);
}
