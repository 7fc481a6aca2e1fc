// The output of a rendered frame (core/frame.h) to files.
//
// write_frame() picks the encoding from the extension, converting colour space in exactly one
// place (color_space.h; srgb8.h is its 8-bit table form):
//   .exr            32-bit float RGBA, linear, unchanged (for compositing and comparisons);
//   .png            8-bit RGBA, RGB sRGB-encoded, alpha linear, written by png_encoder.h;
//   .tif / .tiff    16-bit RGBA, RGB sRGB-encoded, alpha linear;
//   anything else OpenImageIO writes: 8-bit sRGB like PNG.
// The file is written atomically (image_io.h).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "raster/core/error.h"
#include "raster/core/frame.h"
#include "raster/output/frame_writer.h"
#include "raster/output/png_encoder.h"

namespace tessera::output {


// The display encoding of a frame: RGB through linear_to_srgb, alpha clamped, each channel
// quantised to `levels` - 1 (255 or 65535) with rounding to nearest.
std::vector<uint8_t> encode_srgb8(const Frame& frame);
std::vector<uint16_t> encode_srgb16(const Frame& frame);

// The pixel type `path`'s extension stores (see above).
io::PixelType frame_pixel_type(const std::filesystem::path& path);

// True when write_frame can write `path`: PNG, which tessera encodes itself (without loading
// the image codec), or a format OpenImageIO writes.
bool frame_format_supported(const std::filesystem::path& path);

// The error for a frame with `pixels` NaN or infinite pixels, naming the file it was for.
Error non_finite_frame_error(const std::filesystem::path& path, size_t pixels);

// The frame encoded as `path`'s extension asks (see above), ready for write_image or for the
// background FrameWriter (frame_writer.h), in `storage` (a buffer to reuse, e.g.
// FrameWriter::spare_bytes(): one of the frame's size is written over without being cleared
// or faulted in again). Throws tessera::Error, naming the file, for a NaN or infinite value.
OwnedImage encode_frame(const std::filesystem::path& path, const Frame& frame, std::vector<uint8_t> storage = {});

// The compression method OpenImageIO is asked for when writing `path` (image_io.h): the
// settings' EXR compression for .exr, the format's default ("") otherwise.
std::string exr_compression(const std::filesystem::path& path, const FileSettings& settings);

// Writes an image encode_frame made for `path`: PNG through png_encoder.h, other formats
// through OpenImageIO (io/image_io.h); atomically either way. Throws tessera::Error naming
// the file. `png`: an encoder (made with settings.png) whose buffers to reuse, or null.
void write_encoded(const std::filesystem::path& path, const OwnedImage& image, const FileSettings& settings = {},
                   PngEncoder* png = nullptr);

// encode_frame + write_encoded. Throws tessera::Error (unwritable path, unknown extension)
// naming the file.
void write_frame(const std::filesystem::path& path, const Frame& frame, const FileSettings& settings = {});

}  // namespace tessera::output
