// --distribute frames|tiles over MPI (Open MPI). Only rank 0's dispatcher thread (frames) or
// the main thread (tiles, workers) calls MPI, one thread at a time: MPI_THREAD_SERIALIZED.
// Every wait that can be long (the dispatcher's receive, the band gathers, the final barrier)
// polls a non-blocking operation with a short sleep instead of a blocking call, which Open MPI
// implements as a busy loop that would take a core from the ranks still rendering.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>

#include "examples/command.h"
#include "examples/distribute.h"
#include "raster/core/error.h"

namespace tessera::cli {
namespace {

constexpr int kTagRequest = 1;  // worker -> rank 0: Message
constexpr int kTagFrame = 2;    // rank 0 -> worker: int frame, -1 = no more
constexpr int kTagBand = 3;     // worker -> rank 0: Message for one band (done or failed)
constexpr int kTagPixels = 4;   // worker -> rank 0: the band's encoded bytes, after a done Message
// Rows per band boundary: a multiple of the renderers' tile sizes (128 raster, 64 rays), so a
// tile is shaded by one rank only.
constexpr int kBandAlign = 128;

struct Message {
    enum Kind : int32_t { request = 0, failed = 1, done = 2 };
    int32_t kind = request;
    int32_t frame = -1;
    std::array<char, 1000> text{};
    int32_t pixel_type = 0;  // a done band: its PixelType; the byte count follows from it
};

// Waits for a non-blocking operation without spinning: Open MPI's blocking calls poll in a
// busy loop, so a rank that waits for slower ones (at a gather, at the end) would take CPU
// from them on a shared or oversubscribed node. 200 us is far below a frame or a band.
void wait_politely(MPI_Request& request, MPI_Status* status = MPI_STATUS_IGNORE) {
    for (int flag = 0;;) {
        MPI_Test(&request, &flag, status);
        if (flag) return;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
}

void check(int rc, const char* what) {
    if (rc != MPI_SUCCESS) throw Error(std::string("MPI: ") + what + " failed");
}

std::string failure_text(int rank, int frame, const std::string& message) {
    return "rank " + std::to_string(rank) + " failed on frame " + std::to_string(frame) + ": " + message +
           " (rerun with --resume to complete the set)";
}

// MPI_Init_thread / MPI_Finalize around the distribution's life, and the pending list as
// rank 0 has it.
class MpiBase : public Distribution {
public:
    explicit MpiBase(std::vector<int> pending) {
        int provided = 0;
        check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
        if (provided < MPI_THREAD_SERIALIZED) throw Error("MPI: this MPI library does not provide MPI_THREAD_SERIALIZED");
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
        int count = int(pending.size());
        MPI_Bcast(&count, 1, MPI_INT, 0, MPI_COMM_WORLD);
        pending.resize(size_t(count));
        MPI_Bcast(pending.data(), count, MPI_INT, 0, MPI_COMM_WORLD);
        pending_ = std::move(pending);
    }
    ~MpiBase() override {
        if (unwinding()) {
            // An error outside the frame protocol (main prints it next): the other ranks may
            // be waiting for this one, so no barrier and no MPI_Finalize. The rank exits 1
            // and mpirun ends the job.
            std::fprintf(stderr, "tessera: rank %d stops on the error below; the job is aborted\n", rank_);
            return;
        }
        // MPI_Finalize synchronises like a barrier, busily: reach it together, politely.
        MPI_Request barrier;
        MPI_Ibarrier(MPI_COMM_WORLD, &barrier);
        wait_politely(barrier);
        MPI_Finalize();
    }
    int rank() const override { return rank_; }
    int ranks() const override { return ranks_; }
    const std::vector<int>& pending() const override { return pending_; }

protected:
    static bool unwinding() { return std::uncaught_exceptions() > 0; }
    int rank_ = 0, ranks_ = 1;
    std::vector<int> pending_;
};

class MpiFrames final : public MpiBase {
public:
    explicit MpiFrames(std::vector<int> pending) : MpiBase(std::move(pending)) {
        if (rank_ == 0 && ranks_ > 1) dispatcher_ = std::thread([this] { dispatch(); });
    }
    ~MpiFrames() override {
        close();
        if (!dispatcher_.joinable()) return;
        if (unwinding()) dispatcher_.detach();  // it waits for workers that may never answer
        else dispatcher_.join();
    }

    std::optional<int> next_frame() override {
        if (rank_ == 0) return take();
        if (stopped_) return std::nullopt;
        Message m;
        MPI_Send(&m, sizeof m, MPI_BYTE, 0, kTagRequest, MPI_COMM_WORLD);
        int frame = -1;
        MPI_Recv(&frame, 1, MPI_INT, 0, kTagFrame, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        stopped_ = frame < 0;
        return stopped_ ? std::nullopt : std::optional<int>(frame);
    }

    void fail(int frame, const std::string& message) override {
        if (rank_ == 0) {
            record(0, frame, message);
            return;
        }
        stopped_ = failed_ = true;
        failed_frame_ = frame;
        failure_ = message;
    }

    bool finish() override {
        if (rank_ != 0) {
            // Every worker ends with exactly one "done" or "failed", after its last write, so
            // rank 0 hears of a failed final write too.
            Message m;
            m.kind = failed_ ? Message::failed : Message::done;
            m.frame = failed_frame_;
            std::strncpy(m.text.data(), failure_.c_str(), m.text.size() - 1);
            MPI_Send(&m, sizeof m, MPI_BYTE, 0, kTagRequest, MPI_COMM_WORLD);
            return !failed_;
        }
        close();
        if (dispatcher_.joinable()) dispatcher_.join();
        std::lock_guard lock(mutex_);
        if (!failure_.empty()) throw Error(failure_);
        return true;
    }

private:
    std::optional<int> take() {
        std::lock_guard lock(mutex_);
        if (closed_ || next_ >= pending_.size()) return std::nullopt;
        return pending_[next_++];
    }
    void close() {
        std::lock_guard lock(mutex_);
        closed_ = true;
    }
    void record(int rank, int frame, const std::string& message) {
        std::lock_guard lock(mutex_);
        closed_ = true;  // no frames after a failure: the job ends and reports it
        if (failure_.empty()) failure_ = failure_text(rank, frame, message);
    }

    // Rank 0's second thread: answers each worker's request with the next frame (-1: none
    // left), until every worker has said it is done or failed.
    void dispatch() {
        int active = ranks_ - 1;
        while (active > 0) {
            Message m;
            MPI_Request request;
            MPI_Status status;
            MPI_Irecv(&m, sizeof m, MPI_BYTE, MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &request);
            wait_politely(request, &status);
            if (m.kind == Message::request) {
                const int frame = take().value_or(-1);
                MPI_Send(&frame, 1, MPI_INT, status.MPI_SOURCE, kTagFrame, MPI_COMM_WORLD);
            } else {
                if (m.kind == Message::failed) {
                    m.text.back() = '\0';
                    record(status.MPI_SOURCE, m.frame, m.text.data());
                }
                --active;
            }
        }
    }

    std::thread dispatcher_;
    std::mutex mutex_;
    size_t next_ = 0;
    bool closed_ = false;
    std::string failure_;  // rank 0: the job's first failure; a worker: its own
    bool stopped_ = false, failed_ = false;  // workers
    int failed_frame_ = -1;
};

class MpiTiles final : public MpiBase {
public:
    using MpiBase::MpiBase;

    std::optional<int> next_frame() override {
        if (stopped_ || next_ >= pending_.size()) return std::nullopt;
        return pending_[next_++];
    }

    std::pair<int, int> rows(int height) const override { return band(rank_, height); }

    bool gather(int frame_number, Frame& frame, const std::string& failure) override {
        // Everyone learns whether anyone failed before pixels move, so no rank waits forever.
        std::array<char, 1000> mine{};
        std::strncpy(mine.data(), failure.c_str(), mine.size() - 1);
        if (failure.empty()) mine[0] = '\0';
        std::vector<char> all(rank_ == 0 ? mine.size() * size_t(ranks_) : 0);
        MPI_Request request;
        MPI_Igather(mine.data(), int(mine.size()), MPI_CHAR, all.data(), int(mine.size()), MPI_CHAR, 0, MPI_COMM_WORLD,
                    &request);
        wait_politely(request);  // the ranks that finished their band first wait here
        int failed_rank = -1;
        if (rank_ == 0)
            for (int r = 0; r < ranks_ && failed_rank < 0; ++r)
                if (all[size_t(r) * mine.size()] != '\0') failed_rank = r;
        MPI_Bcast(&failed_rank, 1, MPI_INT, 0, MPI_COMM_WORLD);
        if (failed_rank >= 0) {
            stopped_ = true;
            failed_self_ = !failure.empty();
            if (rank_ == 0) failure_ = failure_text(failed_rank, frame_number, &all[size_t(failed_rank) * mine.size()]);
            return false;
        }
        const int row = frame.width * 4;  // floats per row
        std::vector<int> counts(static_cast<size_t>(ranks_)), displs(static_cast<size_t>(ranks_));
        for (int r = 0; r < ranks_; ++r) {
            const auto [y0, y1] = band(r, frame.height);
            counts[size_t(r)] = (y1 - y0) * row;
            displs[size_t(r)] = y0 * row;
        }
        float* pixels = reinterpret_cast<float*>(frame.pixels.data());
        const auto [y0, y1] = rows(frame.height);
        if (rank_ == 0)
            MPI_Igatherv(MPI_IN_PLACE, 0, MPI_FLOAT, pixels, counts.data(), displs.data(), MPI_FLOAT, 0, MPI_COMM_WORLD,
                         &request);
        else
            MPI_Igatherv(pixels + size_t(y0) * size_t(row), (y1 - y0) * row, MPI_FLOAT, nullptr, nullptr, nullptr,
                         MPI_FLOAT, 0, MPI_COMM_WORLD, &request);
        wait_politely(request);
        return rank_ == 0;
    }

    bool stream_bands(int frame_number, const render::BandLayout& layout, const RenderBands& render,
                      const EncodeBand& encode, const WriteBand& write) override {
        std::string failure;  // rank 0: the frame's first failure; a worker: its own
        int failed_rank = -1;
        if (rank_ == 0) {
            const auto fail_with = [&](int rank, const std::string& why) {
                if (failed_rank < 0) failed_rank = rank, failure = why;
            };
            const auto store = [&](int b, output::OwnedImage band) {
                if (failed_rank >= 0) return;  // the frame is lost; its temporary goes
                try {
                    write(b, std::move(band));
                } catch (const std::exception& e) {
                    fail_with(0, e.what());
                }
            };
            // Every other rank's band before `end`, in order: written, or discarded once the
            // frame has failed (the senders must not wait forever).
            int next = 0;
            const auto receive_until = [&](int end) {
                for (; next < end; ++next) {
                    const int from = next % ranks_;
                    if (from == 0) continue;
                    Message m;
                    MPI_Request request;
                    MPI_Irecv(&m, sizeof m, MPI_BYTE, from, kTagBand, MPI_COMM_WORLD, &request);
                    wait_politely(request);
                    if (m.kind == Message::failed) {
                        m.text.back() = '\0';
                        fail_with(from, m.text.data());
                        continue;
                    }
                    const auto [y0, y1] = layout.rows(next);
                    output::OwnedImage band{layout.width, y1 - y0, 4, io::PixelType(m.pixel_type), {}};
                    band.bytes.resize(size_t(band.width) * size_t(band.height) * 4 * io::pixel_type_bytes(band.type));
                    MPI_Irecv(band.bytes.data(), int(band.bytes.size()), MPI_BYTE, from, kTagPixels, MPI_COMM_WORLD,
                              &request);
                    wait_politely(request);
                    store(next, std::move(band));
                }
            };
            try {
                render([&](int b) { return b % ranks_ == 0 && failed_rank < 0; },
                       [&](int b, const Frame& band) {
                           receive_until(b);
                           store(b, encode(band));
                           next = b + 1;
                       });
            } catch (const std::exception& e) {
                fail_with(0, e.what());
            }
            receive_until(layout.bands());
        } else {
            int next = rank_;  // this rank's next band not yet sent
            const auto send = [&](const output::OwnedImage* band, const std::string& why) {
                Message m;
                m.kind = band ? Message::done : Message::failed;
                m.frame = frame_number;
                m.pixel_type = band ? int32_t(band->type) : 0;
                std::strncpy(m.text.data(), why.c_str(), m.text.size() - 1);
                MPI_Request request;
                MPI_Isend(&m, sizeof m, MPI_BYTE, 0, kTagBand, MPI_COMM_WORLD, &request);
                wait_politely(request);
                if (band) {
                    MPI_Isend(band->bytes.data(), int(band->bytes.size()), MPI_BYTE, 0, kTagPixels, MPI_COMM_WORLD,
                              &request);
                    wait_politely(request);  // one band in flight: memory stays one band
                }
                next += ranks_;
            };
            try {
                render([&](int b) { return b % ranks_ == rank_; }, [&](int, const Frame& band) {
                    const output::OwnedImage encoded = encode(band);
                    send(&encoded, "");
                });
            } catch (const std::exception& e) {
                failure = e.what();
            }
            while (next < layout.bands()) send(nullptr, failure.empty() ? "a band was not rendered" : failure);
        }
        // Everyone learns whether the frame failed, and stops after it if so.
        MPI_Request request;
        MPI_Ibcast(&failed_rank, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
        wait_politely(request);
        if (failed_rank < 0) return rank_ == 0;
        stopped_ = true;
        if (rank_ == 0) failure_ = failure_text(failed_rank, frame_number, failure);
        else failed_self_ = !failure.empty();
        return false;
    }

    // A failed write after the last gather (rank 0 writes every frame).
    void fail(int frame, const std::string& message) override {
        failed_self_ = true;
        if (failure_.empty()) failure_ = failure_text(rank_, frame, message);
    }

    bool finish() override {
        if (rank_ == 0 && !failure_.empty()) throw Error(failure_);
        return !failed_self_;
    }

private:
    // Rank r's rows: an even share of the kBandAlign-row bands, in rank order.
    std::pair<int, int> band(int r, int height) const {
        const int bands = (height + kBandAlign - 1) / kBandAlign;
        const auto edge = [&](int k) { return std::min(height, int(int64_t(bands) * k / ranks_) * kBandAlign); };
        return {edge(r), edge(r + 1)};
    }

    size_t next_ = 0;
    bool stopped_ = false, failed_self_ = false;
    std::string failure_;
};

}  // namespace

std::unique_ptr<Distribution> make_mpi_distribution(DistributeMode mode, std::vector<int> pending) {
    if (mode == DistributeMode::tiles) return std::make_unique<MpiTiles>(std::move(pending));
    return std::make_unique<MpiFrames>(std::move(pending));
}

}  // namespace tessera::cli
