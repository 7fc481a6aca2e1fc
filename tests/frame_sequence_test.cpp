#include "examples/frame_sequence.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

using namespace tessera;

TEST(FrameRange, InclusiveAtBothEnds) {
    FrameRange r = parse_frame_range("3:7");
    EXPECT_EQ(r.first, 3);
    EXPECT_EQ(r.last, 7);
    EXPECT_EQ(r.count(), 5);
    EXPECT_EQ(parse_frame_range("12").count(), 1);
}

TEST(FrameRange, BadRangesAreUsageErrors) {
    for (const char* bad : {"7:3", "-1:4", "1:-4", "a:b", "1:", ":2", "1:2:3", "", "1.5:2"})
        EXPECT_THROW(parse_frame_range(bad), std::invalid_argument) << bad;
}

TEST(Shard, PartitionCoversEveryFrameOnce) {
    const FrameRange range = parse_frame_range("1:23");
    for (int count = 1; count <= 7; ++count) {
        std::multiset<int> seen;
        for (int index = 0; index < count; ++index)
            for (int f : frames_of_shard(range, {index, count})) seen.insert(f);
        ASSERT_EQ(int(seen.size()), range.count()) << count << " shards";
        for (int f = range.first; f <= range.last; ++f) EXPECT_EQ(seen.count(f), 1u);
    }
}

TEST(Shard, Parsing) {
    Shard s = parse_shard("2/5");
    EXPECT_EQ(s.index, 2);
    EXPECT_EQ(s.count, 5);
    for (const char* bad : {"5/5", "-1/3", "1/0", "1", "a/b", "1/2/3"})
        EXPECT_THROW(parse_shard(bad), std::invalid_argument) << bad;
}

TEST(FramePattern, HashesAndPrintf) {
    EXPECT_EQ(FramePattern("out/a_####.png").path_for(7), "out/a_0007.png");
    EXPECT_EQ(FramePattern("out/a_##.png").path_for(123), "out/a_123.png");
    EXPECT_EQ(FramePattern("a_%04d.exr").path_for(42), "a_0042.exr");
    EXPECT_EQ(FramePattern("a_%d.tif").path_for(42), "a_42.tif");
    EXPECT_FALSE(FramePattern("still.png").has_placeholder());
    EXPECT_EQ(FramePattern("still.png").path_for(3), "still.png");
}

TEST(FramePattern, MalformedPatternsAreRejected) {
    for (const char* bad : {"a_##_##.png", "a_%s.png", "a_%04x.png", "a_%0d.png", "a_#%d.png",
                            "a_%d%d.png"})
        EXPECT_THROW(FramePattern{bad}, std::invalid_argument) << bad;
}
