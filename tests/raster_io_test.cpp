// Files in and out of the raster command: OBJ (loader errors, fan order, bad vertices), the
// camera file, TSID and PFM.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "raster/io/camera_file.h"
#include "raster/core/error.h"
#include "raster/io/obj_loader.h"
#include "raster/io/visibility_io.h"

namespace tessera {
namespace {

std::string error_of(const std::string& obj) {
    try {
        io::parse_obj(obj, "t.obj");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(RasterIo, ObjFanTriangulatesFromFirstVertexInFileOrder) {
    io::ObjLoadStats stats;
    const Mesh m = io::parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 2 0\nf 1 2 3 4\nf 5 1 3\n", "t.obj", &stats);
    ASSERT_EQ(m.triangle_count(), 3u);
    auto p = [&](size_t t, int k) { return m.positions[m.indices[3 * t + k]]; };
    EXPECT_EQ(p(0, 0), glm::vec3(0, 0, 0));
    EXPECT_EQ(p(0, 1), glm::vec3(1, 0, 0));
    EXPECT_EQ(p(0, 2), glm::vec3(1, 1, 0));
    EXPECT_EQ(p(1, 0), glm::vec3(0, 0, 0));
    EXPECT_EQ(p(1, 2), glm::vec3(0, 1, 0));
    EXPECT_EQ(p(2, 0), glm::vec3(2, 2, 0));
    EXPECT_EQ(stats.faces, 2u);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.uvs.empty());
}

TEST(RasterIo, ObjKeepsNormalsAndUvsPerCorner) {
    const Mesh m = io::parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0.5 0.25\nf 1/1/1 2/1/1 3//1\n", "t.obj");
    ASSERT_EQ(m.triangle_count(), 1u);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    EXPECT_EQ(m.uvs[m.indices[0]], glm::vec2(0.5f, 0.25f));
    EXPECT_EQ(m.uvs[m.indices[2]], glm::vec2(0.0f));  // missing uv: (0,0)
}

TEST(RasterIo, ObjErrorsNameTheProblem) {
    EXPECT_NE(error_of("v 1 2 abc\n").find("line 1"), std::string::npos);
    EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").find("out of range"), std::string::npos);
    EXPECT_NE(error_of("v 0 0\n").find("expected 3 numbers"), std::string::npos);
    EXPECT_NE(error_of("v 0 0 0\nv 1 0 0\nf 1 2\n"), "");
    EXPECT_EQ(error_of("# only a comment\n"), "");
    EXPECT_NE(error_of(std::string("v 0 0 0\n\0\x01\x02", 11)).find("binary"), std::string::npos);
}

TEST(RasterIo, ObjBadVerticesMakeTheirTrianglesDegenerate) {
    io::ObjLoadStats stats;
    const Mesh m = io::parse_obj("v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 1e30 0\nv 1 1 0\nf 1 2 3\nf 1 2 5\nf 4 2 5\n", "t.obj", &stats);
    ASSERT_EQ(m.triangle_count(), 3u);  // ids stay stable
    EXPECT_EQ(stats.bad_vertices, 2u);
    EXPECT_EQ(stats.skipped_triangles, 2u);
    EXPECT_EQ(m.indices[0], m.indices[1]);
    EXPECT_NE(m.indices[3], m.indices[4]);
    for (const glm::vec3& p : m.positions) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
}

TEST(RasterIo, MissingObjFileIsAnError) {
    try {
        io::load_obj("/nonexistent/x.obj");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot read '/nonexistent/x.obj'"), std::string::npos);
    }
}

TEST(RasterIo, WrittenObjReadsBack) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    m.indices = {0, 1, 2};
    const auto path = std::filesystem::temp_directory_path() / "tessera_raster_io_test.obj";
    io::write_obj(path, m);
    const Mesh back = io::load_obj(path);
    std::filesystem::remove(path);
    ASSERT_EQ(back.triangle_count(), 1u);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(back.positions[back.indices[k]], m.positions[k]);
        EXPECT_EQ(back.uvs[back.indices[k]], m.uvs[k]);
    }
}

TEST(RasterIo, CameraFileKeysAndErrors) {
    Camera c;
    io::parse_camera("# cam\neye 1 2 3\nlookat 0 0 -1\nup 0 1 0\nfovy_deg 45\nnear 0.5\nfar 50\n", "c.txt", c);
    EXPECT_EQ(c.eye, glm::vec3(1, 2, 3));
    EXPECT_EQ(c.fovy_deg, 45.0f);
    EXPECT_EQ(c.far, 50.0f);
    EXPECT_NO_THROW(io::validate_camera(c));
    EXPECT_THROW(io::parse_camera("eye 1 2\n", "c.txt", c), Error);
    EXPECT_THROW(io::parse_camera("zoom 3\n", "c.txt", c), Error);
    c.lookat = c.eye;
    EXPECT_THROW(io::validate_camera(c), std::invalid_argument);
}

TEST(RasterIo, TsidAndPfmLayout) {
    VisibilityBuffer v;
    v.reset(3, 2);
    v.triangle = {1, 2, 3, 4, 5, kNoTriangle};
    v.depth = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 1.0f};
    const auto dir = std::filesystem::temp_directory_path();
    io::write_tsid(dir / "t.id", v);
    EXPECT_EQ(io::read_tsid(dir / "t.id").triangle, v.triangle);
    io::write_depth_pfm(dir / "t.pfm", v);
    std::ifstream pfm(dir / "t.pfm", std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(pfm)), {});
    ASSERT_EQ(text.rfind("Pf\n3 2\n-1.0\n", 0), 0u);
    float first;
    std::memcpy(&first, text.data() + std::strlen("Pf\n3 2\n-1.0\n"), 4);
    EXPECT_EQ(first, 0.4f);  // bottom row first
    std::filesystem::remove(dir / "t.id");
    std::filesystem::remove(dir / "t.pfm");
}

// Multisampled ids: the sample count in the header, then the samples of each pixel adjacent;
// one sample keeps the three-field header, and malformed counts are refused.
TEST(RasterIo, TsidPerSample) {
    VisibilityBuffer v;
    v.reset(2, 1);
    v.samples = 4;
    v.sample_triangle = {0, 1, 2, 3, 4, 5, 6, kNoTriangle};
    const auto dir = std::filesystem::temp_directory_path();
    io::write_tsid(dir / "ms.id", v);
    std::ifstream file(dir / "ms.id", std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(file)), {});
    ASSERT_EQ(text.size(), std::strlen("TSID 2 1 4\n") + 8 * 4);
    EXPECT_EQ(text.rfind("TSID 2 1 4\n", 0), 0u);
    uint32_t second_pixel_first_sample;
    std::memcpy(&second_pixel_first_sample, text.data() + std::strlen("TSID 2 1 4\n") + 4 * 4, 4);
    EXPECT_EQ(second_pixel_first_sample, 4u);
    const VisibilityBuffer back = io::read_tsid(dir / "ms.id");
    EXPECT_EQ(back.samples, 4);
    EXPECT_EQ(back.sample_triangle, v.sample_triangle);
    EXPECT_EQ(back.triangle.size(), 2u);

    v.sample_triangle.pop_back();  // not one id per sample
    EXPECT_THROW(io::write_tsid(dir / "ms.id", v), std::invalid_argument);
    for (const char* header : {"TSID 2 1 3\n", "TSID 2 1 1\n", "TSID 2 1 x\n", "TSID 2 1 4 \n"}) {
        std::ofstream(dir / "bad.id", std::ios::binary) << header << std::string(8 * 4, '\0');
        EXPECT_THROW(io::read_tsid(dir / "bad.id"), Error) << header;
    }
    std::ofstream(dir / "short.id", std::ios::binary) << "TSID 2 1 4\n" << std::string(7 * 4, '\0');
    EXPECT_THROW(io::read_tsid(dir / "short.id"), Error);
}

}  // namespace
}  // namespace tessera
