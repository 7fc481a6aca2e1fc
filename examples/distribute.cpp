#include "examples/distribute.h"

#include "examples/command.h"
#include "raster/core/error.h"

namespace tessera::cli {

DistributeMode parse_distribute(std::string_view text) {
    if (text.empty()) return DistributeMode::none;
    if (text == "frames") return DistributeMode::frames;
    if (text == "tiles") return DistributeMode::tiles;
    throw UsageError("--distribute: unknown mode '" + std::string(text) + "' (expected frames or tiles)");
}

namespace {

class LocalFrames final : public Distribution {
public:
    explicit LocalFrames(std::vector<int> pending) : pending_(std::move(pending)) {}
    const std::vector<int>& pending() const override { return pending_; }
    std::optional<int> next_frame() override {
        if (next_ >= pending_.size()) return std::nullopt;
        return pending_[next_++];
    }
    void fail(int, const std::string&) override {}
    bool finish() override { return true; }

private:
    std::vector<int> pending_;
    size_t next_ = 0;
};

}  // namespace

std::unique_ptr<Distribution> make_distribution(DistributeMode mode, std::vector<int> pending) {
    if (mode == DistributeMode::none) return std::make_unique<LocalFrames>(std::move(pending));
    return make_mpi_distribution(mode, std::move(pending));
}

}  // namespace tessera::cli
