#include "raster/output/frame_writer.h"

#include "raster/core/trace.h"
#include "raster/output/frame_encoding.h"

namespace tessera::output {

FrameWriter::FrameWriter(size_t max_pending, const FileSettings& settings)
    : max_pending_(max_pending == 0 ? 1 : max_pending), settings_(settings), png_(settings.png), worker_([this] { run(); }) {}

FrameWriter::~FrameWriter() {
    {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return queue_.empty() && in_flight_ == 0; });
        stopping_ = true;
    }
    changed_.notify_all();
    worker_.join();
}

void FrameWriter::rethrow_failure_locked() {
    if (failure_) {
        std::exception_ptr failure = failure_;
        failure_ = nullptr;
        std::rethrow_exception(failure);
    }
}

void FrameWriter::submit(std::filesystem::path path, OwnedImage image) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() + in_flight_ < max_pending_ || failure_; });
    rethrow_failure_locked();
    queue_.push_back({std::move(path), std::move(image)});
    changed_.notify_all();
}

void FrameWriter::finish() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return (queue_.empty() && in_flight_ == 0) || failure_; });
    rethrow_failure_locked();
}

std::vector<std::filesystem::path> FrameWriter::written() const {
    std::lock_guard lock(mutex_);
    return written_;
}

void FrameWriter::record_written(std::filesystem::path path) {
    std::lock_guard lock(mutex_);
    written_.push_back(std::move(path));
}

std::vector<uint8_t> FrameWriter::spare_bytes() {
    std::lock_guard lock(mutex_);
    if (spare_.empty()) return {};
    std::vector<uint8_t> bytes = std::move(spare_.back());
    spare_.pop_back();
    return bytes;
}

void FrameWriter::run() {
    for (;;) {
        Job job;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
            if (queue_.empty()) return;
            job = std::move(queue_.front());
            queue_.pop_front();
            ++in_flight_;
        }
        std::exception_ptr failure;
        try {
            TraceScope scope("write frame", "io");
            write_encoded(job.path, job.image, settings_, &png_);
        } catch (...) {
            failure = std::current_exception();
        }
        {
            std::lock_guard lock(mutex_);
            --in_flight_;
            if (failure) {
                if (!failure_) failure_ = failure;
                queue_.clear();  // frames after a failed one are not written
            } else {
                written_.push_back(job.path);
            }
            if (spare_.size() <= max_pending_) spare_.push_back(std::move(job.image.bytes));
        }
        changed_.notify_all();
    }
}

}  // namespace tessera::output
