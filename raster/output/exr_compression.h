// How OpenEXR frames are compressed (--exr). All but dwaa are lossless:
//   zip   deflate per block of 16 scanlines: OpenImageIO's default, so the default here;
//   piz   wavelet transform then Huffman coding, per 32 scanlines: usually smaller than zip on
//         rendered frames with texture and noise, slower to write;
//   dwaa  lossy DCT of the colour channels (OpenEXR's DWA, 32 scanlines; alpha and other
//         channels stay lossless): the smallest files, for review rather than compositing;
//   none  uncompressed.
// BENCHMARKS.md has time and size per frame for each.
#pragma once
#include <string_view>

namespace tessera::output {

enum class ExrCompression { none, zip, piz, dwaa };

// "none", "zip", "piz" or "dwaa"; throws std::invalid_argument naming the accepted values.
ExrCompression parse_exr_compression(std::string_view name);

// The method's name, as OpenImageIO's "compression" attribute takes it.
const char* exr_compression_name(ExrCompression compression);

}  // namespace tessera::output
