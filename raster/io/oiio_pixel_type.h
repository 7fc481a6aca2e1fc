// PixelType (image_io.h) as OpenImageIO's TypeDesc: shared by the whole-image and the
// streamed writers, kept out of image_io.h so that users of images need no OpenImageIO header.
#pragma once
#include <OpenImageIO/typedesc.h>

#include "raster/io/image_io.h"

namespace tessera::io {

inline OIIO::TypeDesc oiio_type(PixelType type) {
    switch (type) {
        case PixelType::u8: return OIIO::TypeDesc::UINT8;
        case PixelType::u16: return OIIO::TypeDesc::UINT16;
        case PixelType::f32: return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::UNKNOWN;
}

}  // namespace tessera::io
