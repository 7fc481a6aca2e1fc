#include "examples/farm/checkpoint_store.h"

#include <charconv>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>
#include <vector>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/core/trace.h"

namespace tessera::farm {

namespace fs = std::filesystem;

CheckpointStore::CheckpointStore(fs::path dir, std::string scene, uint64_t fingerprint, int every)
    : dir_(std::move(dir)), every_(every) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fingerprint));
    prefix_ = scene + "-" + hex + "-";
}

fs::path CheckpointStore::path_for(int frame) const {
    char digits[16];
    std::snprintf(digits, sizeof digits, "%08d", frame);
    return dir_ / (prefix_ + digits + ".sim");
}

std::optional<int> CheckpointStore::latest(int after, int up_to) const {
    std::optional<int> best;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir_, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.size() != prefix_.size() + 12 || name.compare(0, prefix_.size(), prefix_) != 0 ||
            name.compare(name.size() - 4, 4, ".sim") != 0)
            continue;
        int f = 0;
        const char* digits = name.data() + prefix_.size();
        const auto [ptr, err] = std::from_chars(digits, digits + 8, f);
        if (err != std::errc() || ptr != digits + 8) continue;
        if (f > after && f <= up_to && (!best || f > *best)) best = f;
    }
    return best;
}

void CheckpointStore::save(int frame, const SceneSimulation& simulation) const {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (!fs::is_directory(dir_))
        throw Error("cannot write checkpoints to '" + dir_.string() + "': " + (ec ? ec.message() : "not a directory"));
    TraceScope t("checkpoint", "io");
    const std::vector<std::byte> bytes = simulation.checkpoint();
    write_file_atomically(path_for(frame), bytes);
}

namespace {

std::vector<std::byte> read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.eof() && in.fail()) throw Error("cannot read checkpoint '" + p.string() + "'");
    std::vector<std::byte> out(chars.size());
    std::memcpy(out.data(), chars.data(), chars.size());
    return out;
}

}  // namespace

int advance(SceneSimulation& simulation, const CheckpointStore* store, int frame) {
    if (simulation.empty() || simulation.frame() == frame) return 0;
    if (store) {
        // Only checkpoints after the held state help (unless that state is past `frame`).
        const std::optional<int> held = simulation.frame();
        const int after = held && *held < frame ? *held : std::numeric_limits<int>::min();
        int up_to = frame;
        while (const std::optional<int> c = store->latest(after, up_to)) {
            const fs::path path = store->path_for(*c);
            try {
                TraceScope t("restore checkpoint", "io");
                simulation.restore(read_bytes(path), path.string());
                break;
            } catch (const Error& e) {
                std::fprintf(stderr, "tessera: warning: %s; not using it\n", e.what());
                up_to = *c - 1;  // an older one may still serve
            }
        }
    }
    const std::optional<int> held = simulation.frame();
    if (held == frame) return 0;
    // From the held state forwards, or from step 0 when it is past `frame` (advance_to
    // starts over then); stopping at each due checkpoint to save it.
    const int start = held && *held < frame ? *held + 1 : 0;
    for (int f = start; f <= frame; ++f) {
        const bool save = store && store->due(f);
        if (f != frame && !save) continue;
        simulation.advance_to(f);
        std::error_code ec;
        if (save && !fs::exists(store->path_for(f), ec)) store->save(f, simulation);
    }
    return frame - start + 1;
}

}  // namespace tessera::farm
