#include "raster/core/trace.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

using namespace tessera;

TEST(Trace, InactiveScopesRecordNothing) {
    Trace trace;
    { TraceScope scope("raster"); }
    EXPECT_EQ(trace.event_count(), 0u);
}

TEST(Trace, WritesValidChromeTraceWithOneTrackPerThread) {
    Trace trace;
    trace.activate();
    {
        TraceScope frame("frame", "frame", 1);
        tbb::parallel_for(0, 64, [](int tile) { TraceScope scope("tile", "tile", tile % 8, tile / 8); });
    }
    trace.deactivate();
    { TraceScope after("ignored"); }
    EXPECT_EQ(trace.event_count(), 65u);

    const auto path = std::filesystem::temp_directory_path() / "tessera_trace_test.json";
    trace.write(path);
    std::ifstream in(path);
    const nlohmann::json json = nlohmann::json::parse(in);  // throws if malformed
    size_t slices = 0, tiles = 0;
    std::set<int> tracks, named;
    bool main_named = false;
    for (const auto& e : json.at("traceEvents")) {
        if (e.at("ph") == "X") {
            ++slices;
            tracks.insert(e.at("tid").get<int>());
            if (e.at("name") == "tile") {
                ++tiles;
                EXPECT_TRUE(e.at("args").contains("x"));
                EXPECT_GE(e.at("dur").get<double>(), 0.0);
            }
        } else if (e.at("name") == "thread_name") {
            named.insert(e.at("tid").get<int>());
            main_named |= e.at("args").at("name") == "main";
        }
    }
    EXPECT_EQ(slices, 65u);
    EXPECT_EQ(tiles, 64u);
    EXPECT_EQ(tracks, named);  // every track that has slices has a name
    EXPECT_TRUE(main_named);
}
