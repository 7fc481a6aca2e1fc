// Whether a frame file on disk is whole: how `render --resume` tells a finished frame from
// one a crash, a full disk or a bad copy cut short or damaged, to render it again. Reading
// only the header (as before) took a PNG truncated after its header for complete, and the
// set stayed broken for ever; so the file is checked to its end:
//   PNG (ISO/IEC 15948): every chunk from IHDR to IEND, which must end the file, with its
//       CRC-32 (so any truncated or overwritten byte is found);
//   TIFF and BigTIFF (TIFF 6.0): every strip or tile of the first image lies within the file,
//       nothing follows the last of them, the directory and its out-of-line values, and
//       deflate-compressed ones (as tessera writes them) inflate to the end of their zlib
//       stream, whose Adler-32 checks their bytes; others are decoded;
//   OpenEXR: every chunk of the offset table lies within the file and the last one ends it;
//       ZIP chunks inflate to the end of their zlib stream (Adler-32); then, as for anything
//       else, OpenImageIO decodes every pixel, a band of rows at a time.
// The image must also be width x height. Memory stays at a band or a strip, whatever the size.
#pragma once
#include <filesystem>

namespace tessera::io {

bool image_is_complete(const std::filesystem::path& path, int width, int height);

}  // namespace tessera::io
