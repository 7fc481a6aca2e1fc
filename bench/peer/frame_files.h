// The frame outputs shared with `tessera raster` (issue 3), written atomically.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

namespace tessera::peer {

// ASCII header "TSID <width> <height>\n", then width*height little-endian uint32 triangle
// ids, rows top to bottom, 0xFFFFFFFF where nothing covers.
void write_triangle_ids(const std::filesystem::path& path, int width, int height,
                        const std::vector<uint32_t>& ids);

// PFM ("Pf", one channel, little-endian scale -1.0), rows bottom to top as the format wants;
// `depth` arrives with rows top to bottom.
void write_depth_pfm(const std::filesystem::path& path, int width, int height,
                     const std::vector<float>& depth);

}  // namespace tessera::peer
