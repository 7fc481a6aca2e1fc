// The date an image file records. OpenImageIO stamps EXR and TIFF files with the time of
// writing (their DateTime attribute) unless told otherwise, so the same frame rendered twice,
// or with 1 and 2 threads, would differ in its bytes. tessera's files record no date, unless
// the environment sets SOURCE_DATE_EPOCH (the reproducible-builds.org convention: seconds
// since 1970-01-01 UTC), whose time every file then carries.
#pragma once
#include <string>

namespace tessera::io {

// "YYYY:MM:DD HH:MM:SS" (TIFF's DateTime form) of SOURCE_DATE_EPOCH in UTC, or "" when it is
// not set; "" as OpenImageIO's "DateTime" attribute leaves the date out. Throws
// tessera::Error for a value that is not a whole number of seconds in 0 .. 253402300799
// (year 9999), as the convention asks.
std::string image_date_time();

}  // namespace tessera::io
