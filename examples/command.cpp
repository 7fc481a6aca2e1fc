#include "examples/command.h"

#include <charconv>

namespace tessera::cli {

namespace {
std::vector<Entry>& registry() {
    static std::vector<Entry> entries;  // function-local: safe from static-init order
    return entries;
}
}  // namespace

Registration::Registration(int order, Define define) {
    registry().push_back({order, std::move(define)});
}

const std::vector<Entry>& registered_commands() { return registry(); }

void parse_size(const std::string& text, const char* flag, int& width, int& height) {
    const auto x = text.find_first_of("xX");
    auto number = [&](std::string_view part, int& value) {
        const char* end = part.data() + part.size();
        auto [ptr, ec] = std::from_chars(part.data(), end, value);
        return ec == std::errc() && ptr == end && value > 0;
    };
    std::string_view all(text);
    if (x == std::string::npos || !number(all.substr(0, x), width) ||
        !number(all.substr(x + 1), height))
        throw UsageError(std::string(flag) + " expects WIDTHxHEIGHT with positive integers, got '" +
                         text + "'");
}

void add_threads_option(CLI::App& command, int& threads) {
    command.add_option("--threads", threads, "worker threads (0 = all cores)")
        ->check(CLI::Range(0, 4096))
        ->default_val(0);
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 size_t(threads));
}

}  // namespace tessera::cli
