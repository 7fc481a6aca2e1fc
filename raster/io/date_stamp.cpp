#include "raster/io/date_stamp.h"

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <string_view>

#include "raster/core/error.h"

namespace tessera::io {

std::string image_date_time() {
    const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
    if (!epoch) return "";
    const std::string_view text(epoch);
    int64_t seconds = -1;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seconds);
    if (ec != std::errc() || end != text.data() + text.size() || seconds < 0 || seconds > 253402300799)
        throw Error("SOURCE_DATE_EPOCH='" + std::string(text) + "' is not a whole number of seconds since 1970");
    const std::time_t t = std::time_t(seconds);
    std::tm utc{};
    gmtime_r(&t, &utc);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y:%m:%d %H:%M:%S", &utc);
    return stamp;
}

}  // namespace tessera::io
