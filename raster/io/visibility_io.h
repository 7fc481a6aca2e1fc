// Files of a VisibilityBuffer, as `tessera raster` writes them (issue 3):
// - TSID: ASCII header "TSID <width> <height>\n", then width*height little-endian uint32
//   triangle ids, rows top to bottom, 0xFFFFFFFF where nothing covers. A multisampled
//   buffer (samples > 1, its per-sample ids kept) is written with the sample count as a
//   fourth header field, "TSID <width> <height> <samples>\n", then width*height*samples ids:
//   pixels in the same order, the samples of a pixel adjacent in sample_pattern.h's order
//   (VisibilityBuffer::sample_index). One sample keeps the three-field header.
// - PFM depth: "Pf\n<width> <height>\n-1.0\n" (negative scale = little-endian), then float32
//   window depth, rows BOTTOM to top as the format requires, 1.0 where empty.
// Both are written atomically (atomic_file.h).
#pragma once
#include <filesystem>

#include "raster/core/visibility.h"

namespace tessera::io {

void write_tsid(const std::filesystem::path& path, const VisibilityBuffer& visibility);
void write_depth_pfm(const std::filesystem::path& path, const VisibilityBuffer& visibility);

// Reads a TSID file back (for tests and tools); throws tessera::Error when malformed. A
// multisampled file fills samples and sample_triangle, and leaves triangle empty (kNoTriangle).
VisibilityBuffer read_tsid(const std::filesystem::path& path);

}  // namespace tessera::io
