// How the frames of one `tessera render` are shared among processes:
//   none    this process renders its frames in order (a farm task: --shard, --claim);
//   frames  MPI: rank 0 hands out frames on demand, one at a time, to whichever rank asks
//           (itself included), so a slow frame never stalls the others; each rank renders
//           with its own TBB threads and writes its own frames;
//   tiles   MPI: every rank renders every frame but shades only its band of rows
//           (FrameRenderer::set_rows); the bands are gathered to rank 0, which writes.
//           Frames too large for memory (band_layout.h) go band by band instead: band b is
//           rendered by rank b % ranks alone and sent to rank 0, which streams the bands into
//           the file in order, so no rank ever holds the frame.
// A rank that fails hands its error to rank 0, which stops handing out work, lets the other
// ranks finish their frames and exits naming the rank and the frame.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "raster/output/frame_encoding.h"
#include "raster/render/frame_renderer.h"

namespace tessera::cli {

enum class DistributeMode { none, frames, tiles };

// "" -> none, "frames", "tiles"; throws UsageError otherwise.
DistributeMode parse_distribute(std::string_view text);

class Distribution {
public:
    virtual ~Distribution() = default;
    virtual int rank() const { return 0; }
    virtual int ranks() const { return 1; }
    // The frames still to render, as rank 0 found them (rank 0's list is broadcast, so every
    // rank agrees even if files appear while the job starts).
    virtual const std::vector<int>& pending() const = 0;
    // The next frame this rank renders; nullopt when there is none left (or a rank failed).
    virtual std::optional<int> next_frame() = 0;
    // The rows [first, second) this rank shades (tiles mode; the whole frame otherwise).
    virtual std::pair<int, int> rows(int height) const { return {0, height}; }
    // Tiles mode: sends this rank's rows to rank 0 and returns true there, with `frame`
    // complete. `failure` non-empty: this rank failed on the frame; every rank then gets
    // false and finish() reports it. Other modes: returns true.
    virtual bool gather(int frame_number, Frame& frame, const std::string& failure) { return failure.empty(); }
    // A frame rendered in bands: render(mine, deliver) renders the bands mine(b) selects and
    // delivers each in order; encode(pixels) turns a band into the file's encoding (where it
    // was rendered: an 8-bit band is a quarter of the floats to send); write(b, encoded)
    // stores band b (bands arrive in order from 0). Locally every band is rendered and
    // written, and failures are thrown. Tiles mode: see above; failures are exchanged
    // instead, and the result is as gather()'s.
    using RenderBands = std::function<void(const render::FrameRenderer::BandFilter&, const render::FrameRenderer::BandSink&)>;
    using EncodeBand = std::function<output::OwnedImage(const Frame&)>;
    using WriteBand = std::function<void(int band, output::OwnedImage encoded)>;
    virtual bool stream_bands(int frame_number, const render::BandLayout& layout, const RenderBands& render,
                              const EncodeBand& encode, const WriteBand& write) {
        (void)frame_number;
        (void)layout;
        render([](int) { return true; }, [&](int b, const Frame& band) { write(b, encode(band)); });
        return true;
    }
    // This rank failed on `frame` (frames mode): rank 0 learns of it, no more frames follow.
    virtual void fail(int frame, const std::string& message) = 0;
    // Waits for the other ranks. Throws tessera::Error naming the failed rank and frame on
    // rank 0; returns false on a rank that failed (it exits 1 without repeating the message).
    virtual bool finish() = 0;
};

// `pending` in order, this process alone, or across MPI ranks (the MPI modes throw
// UsageError in a build without MPI).
std::unique_ptr<Distribution> make_distribution(DistributeMode mode, std::vector<int> pending);

// Implemented by distribute/mpi.cpp in an MPI build and distribute/no_mpi.cpp otherwise.
std::unique_ptr<Distribution> make_mpi_distribution(DistributeMode mode, std::vector<int> pending);

}  // namespace tessera::cli
