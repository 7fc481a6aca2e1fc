// Growing skins and their checkpoints (raster/farm/scene_simulation.h, checkpoint_store.h):
// the state of frame k is the same reached directly, frame by frame, backwards, or from a
// checkpoint; damaged or foreign checkpoints are refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "raster/core/error.h"
#include "examples/farm/checkpoint_store.h"
#include "examples/farm/scene_simulation.h"
#include "raster/scene_file/scene_parse.h"

namespace tessera::farm {
namespace {

namespace fs = std::filesystem;

scene_file::SceneSpec growing_skin_scene(int grow_per_frame, int seed = 5) {
    const std::string json = R"({"textures": {"skin": {"type": "reaction_diffusion", "preset": "spots", "size": 32,
        "steps": 50, "seed": )" + std::to_string(seed) + R"(, "grow_per_frame": )" + std::to_string(grow_per_frame) +
                             R"(}}, "materials": {"m": {"diffuse_texture": "skin"}},
        "objects": [{"type": "sphere", "material": "m"}]})";
    std::vector<std::string> warnings;
    return scene_file::parse_scene(json, "test", warnings);
}

TEST(SceneSimulation, StaticSkinsAreNotSimulated) {
    EXPECT_TRUE(SceneSimulation(growing_skin_scene(0).textures).empty());
}

TEST(SceneSimulation, StateOfAFrameIsPathIndependent) {
    const std::vector<scene_file::TextureSpec> skins = growing_skin_scene(7).textures;
    SceneSimulation direct(skins), stepwise(skins), backwards(skins);
    direct.advance_to(9);
    for (int f = 0; f <= 9; ++f) stepwise.advance_to(f);
    backwards.advance_to(12);
    backwards.advance_to(9);  // starts over from step 0
    EXPECT_EQ(direct.checkpoint(), stepwise.checkpoint());
    EXPECT_EQ(direct.checkpoint(), backwards.checkpoint());
    SceneSimulation other(skins);
    other.advance_to(8);
    EXPECT_NE(direct.checkpoint(), other.checkpoint());  // the skin grows
}

TEST(SceneSimulation, RestoreThenAdvanceMatchesDirect) {
    const std::vector<scene_file::TextureSpec> skins = growing_skin_scene(7).textures;
    SceneSimulation a(skins), b(skins), direct(skins);
    a.advance_to(4);
    b.restore(a.checkpoint(), "memory");
    EXPECT_EQ(b.frame(), 4);
    b.advance_to(9);
    direct.advance_to(9);
    EXPECT_EQ(b.checkpoint(), direct.checkpoint());
    EXPECT_EQ(a.checkpoint().size(), a.checkpoint_size());
}

TEST(SceneSimulation, RefusesDamagedTruncatedAndForeignCheckpoints) {
    const std::vector<scene_file::TextureSpec> skins = growing_skin_scene(7).textures;
    SceneSimulation a(skins), b(skins);
    a.advance_to(3);
    b.advance_to(1);
    std::vector<std::byte> bytes = a.checkpoint();
    bytes[bytes.size() / 2] ^= std::byte{1};
    EXPECT_THROW(b.restore(bytes, "x"), Error);
    EXPECT_EQ(b.frame(), 1);  // unchanged
    bytes = a.checkpoint();
    bytes.resize(bytes.size() - 9);
    EXPECT_THROW(b.restore(bytes, "x"), Error);
    SceneSimulation foreign(growing_skin_scene(7, 6).textures);
    EXPECT_NE(foreign.fingerprint(), a.fingerprint());
    EXPECT_THROW(foreign.restore(a.checkpoint(), "x"), Error);
}

TEST(CheckpointStore, SavesDueFramesAndRestoresTheLatest) {
    const fs::path dir = fs::temp_directory_path() / ("tessera_ckpt_" + std::to_string(getpid()));
    fs::remove_all(dir);
    const std::vector<scene_file::TextureSpec> skins = growing_skin_scene(5).textures;
    SceneSimulation writer(skins);
    const CheckpointStore store(dir, "grow", writer.fingerprint(), 3);
    EXPECT_EQ(advance(writer, &store, 7), 8);  // frames 0..7 from scratch
    for (int f : {0, 3, 6}) EXPECT_TRUE(fs::exists(store.path_for(f))) << f;
    EXPECT_FALSE(fs::exists(store.path_for(7)));
    EXPECT_EQ(store.latest(-1, 7), 6);
    EXPECT_EQ(store.latest(6, 7), std::nullopt);

    SceneSimulation reader(skins), direct(skins);
    EXPECT_EQ(advance(reader, &store, 8), 2);  // restores 6, simulates 7 and 8
    direct.advance_to(8);
    EXPECT_EQ(reader.checkpoint(), direct.checkpoint());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace tessera::farm
