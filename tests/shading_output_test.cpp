// The colour-space conversion and frame output (PNG 8-bit sRGB, EXR float linear, TIFF 16-bit).
#include <gtest/gtest.h>

#include <filesystem>

#include "raster/core/error.h"
#include "raster/io/image_io.h"
#include "raster/core/color_space.h"
#include "raster/output/frame_encoding.h"
#include "raster/scene/material.h"

using namespace tessera;

TEST(ShadingOutput, SrgbTransferFunction) {
    EXPECT_EQ(linear_to_srgb(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
    EXPECT_NEAR(linear_to_srgb(0.0031308f), 0.04045f, 1e-5f);  // the two pieces meet
    EXPECT_NEAR(linear_to_srgb(0.5f), 0.735357f, 1e-5f);
    EXPECT_NEAR(linear_to_srgb(0.18f), 0.461356f, 1e-5f);
    EXPECT_EQ(linear_to_srgb(-1.0f), 0.0f);
    EXPECT_EQ(linear_to_srgb(7.0f), 1.0f);
    EXPECT_EQ(linear_to_srgb(NAN), 0.0f);
    for (float x = 0.0f; x <= 1.0f; x += 0.01f) EXPECT_NEAR(srgb_to_linear(linear_to_srgb(x)), x, 1e-5f);
}

TEST(ShadingOutput, FramesRoundTripThroughEachFormat) {
    Frame frame(3, 2, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    frame.at(0, 0) = {0.5f, 0.18f, 1.0f, 1.0f};
    frame.at(2, 1) = {4.0f, -1.0f, 0.0f, 1.0f};  // out of range: clamped for display only
    frame.at(1, 1) = {0.0f, 0.0f, 0.0f, 0.5f};
    const auto dir = std::filesystem::temp_directory_path() / "tessera_shading_output_test";
    std::filesystem::create_directories(dir);

    output::write_frame(dir / "f.exr", frame);
    const io::FloatImage exr = io::read_image(dir / "f.exr");
    ASSERT_EQ(exr.channels, 4);
    EXPECT_EQ(exr.at(2, 1, 0), 4.0f);  // linear floats kept as they are
    EXPECT_EQ(exr.at(2, 1, 1), -1.0f);

    output::write_frame(dir / "f.png", frame);
    const io::FloatImage png = io::read_image(dir / "f.png");
    EXPECT_EQ(int(png.at(0, 0, 0) * 255.0f + 0.5f), 188);  // 0.735357 * 255 rounded
    EXPECT_EQ(int(png.at(2, 1, 0) * 255.0f + 0.5f), 255);
    EXPECT_EQ(int(png.at(1, 1, 3) * 255.0f + 0.5f), 128);  // alpha stays linear

    output::write_frame(dir / "f.tif", frame);
    const io::FloatImage tif = io::read_image(dir / "f.tif");
    EXPECT_NEAR(tif.at(0, 0, 1), linear_to_srgb(0.18f), 1.0f / 65535.0f);

    EXPECT_THROW(output::write_frame(dir / "no_such_dir" / "f.png", frame), Error);
}

TEST(ShadingMaterial, UnknownOrUnusedParametersWarnBadValuesThrow) {
    scene::Material m;
    const std::vector<scene::MaterialParameter> params = {
        {"kd", {0.8f, 0.2f, 0.1f}, ""}, {"model", {}, "toon"}, {"ks", {0.5f}, ""}, {"glossiness", {3.0f}, ""}};
    const std::vector<std::string> warnings = scene::set_material_parameters(m, params);
    EXPECT_EQ(m.model, scene::ShadingModel::toon);  // applied first, whatever the order
    EXPECT_EQ(m.kd, glm::vec3(0.8f, 0.2f, 0.1f));
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_NE(warnings[0].find("'ks' is not used by the toon model"), std::string::npos);
    EXPECT_NE(warnings[1].find("'glossiness' is unknown"), std::string::npos);

    const std::vector<scene::MaterialParameter> bad_count = {{"kd", {1.0f, 2.0f}, ""}};
    EXPECT_THROW(scene::set_material_parameters(m, bad_count), std::invalid_argument);
    const std::vector<scene::MaterialParameter> bad_model = {{"model", {}, "glossy"}};
    EXPECT_THROW(scene::set_material_parameters(m, bad_model), std::invalid_argument);
    const std::vector<scene::MaterialParameter> bad_opacity = {{"opacity", {1.5f}, ""}};
    EXPECT_THROW(scene::set_material_parameters(m, bad_opacity), std::invalid_argument);
}
