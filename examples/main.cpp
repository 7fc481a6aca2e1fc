// The `tessera` command: parses the command line with CLI11, runs the chosen subcommand, and
// turns every failure into one line on stderr and an exit code (see command.h).
#include <embree3/rtcore_config.h>
#include <oneapi/tbb/version.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <new>

#include "examples/command.h"
#include "examples/signals.h"
#include "raster/core/error.h"
#include "raster/io/date_stamp.h"
#include "raster/io/image_codec.h"

namespace {

std::string version_text() {
    std::string text = "tessera " TESSERA_VERSION "\n";
    text += "  embree " RTC_VERSION_STRING ", oneTBB " TBB_VERSION_STRING ", OpenImageIO ";
    try {  // the image codec module, loaded here as on the first image (io/image_codec.h)
        text += tessera::io::image_codec().library_version() + "\n";
    } catch (const tessera::Error& e) {
        text += std::string("unavailable\n  ") + e.what() + "\n";
    }
    text += "  built for: ";
#if defined(__AVX512F__)
    text += "AVX-512";
#elif defined(__AVX2__)
    text += "AVX2";
#else
    text += "generic x86-64 (scalar SIMD fallback)";
#endif
    return text;
}

void print_error(const std::string& message, const std::string& hint) {
    std::fprintf(stderr, "tessera: error: %s\n", message.c_str());
    if (!hint.empty()) std::fprintf(stderr, "hint: %s\n", hint.c_str());
}

// "tessera generate rd": the chain of subcommands the user typed, for the --help hint.
std::string deepest_command(const CLI::App& app) {
    std::string name = "tessera";
    for (const CLI::App* level = &app;;) {
        const auto chosen = level->get_subcommands();
        if (chosen.empty()) return name;
        level = chosen.front();
        name += " " + level->get_name();
    }
}

// CLI11 messages sometimes span lines; the contract is one line.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace tessera::cli;
    end_cleanly_on_signals();  // no command leaves a temporary behind on SIGTERM (signals.h)
    CLI::App app{"tessera: a tiled SIMD CPU rasterizer, an Embree ray tracer and procedural "
                 "generators, rendering the same scenes",
                 "tessera"};
    app.set_version_flag("--version", std::function<std::string()>(version_text));  // only when asked
    app.require_subcommand(1);
    app.footer("Run 'tessera COMMAND --help' for a command's options.");

    std::vector<Entry> commands = registered_commands();
    std::stable_sort(commands.begin(), commands.end(),
                     [](const Entry& a, const Entry& b) { return a.order < b.order; });
    std::map<const CLI::App*, Run> runs;
    for (const Entry& entry : commands) {
        const size_t before = app.get_subcommands({}).size();
        Run run = entry.define(app);
        runs[app.get_subcommands({}).at(before)] = std::move(run);
    }

    std::string hint_command = "tessera";
    try {
        try {
            app.parse(argc, argv);
        } catch (const CLI::Success& done) {
            return app.exit(done);  // --help, --version
        } catch (const CLI::ParseError& error) {
            hint_command = deepest_command(app);
            if (app.get_subcommands().empty() && error.get_name() == "RequiredError")
                print_error("no command given", "run 'tessera --help' to list the commands");
            else
                print_error(one_line(error.what()), "run '" + hint_command + " --help' for usage");
            return 2;
        }
        // A malformed SOURCE_DATE_EPOCH fails before any work, not at the first file written.
        (void)tessera::io::image_date_time();
        for (const CLI::App* sub : app.get_subcommands()) {
            hint_command = deepest_command(app);
            return runs.at(sub)();
        }
        return 2;
    } catch (const UsageError& error) {
        print_error(error.what(), "run '" + hint_command + " --help' for usage");
        return 2;
    } catch (const std::invalid_argument& error) {
        print_error(error.what(), "run '" + hint_command + " --help' for usage");
        return 2;
    } catch (const tessera::Error& error) {
        print_error(error.what(), "");
        return 1;
    } catch (const std::bad_alloc&) {
        print_error("out of memory", "");
        return 1;
    } catch (const std::exception& error) {
        print_error(error.what(), "");
        return 1;
    }
}
