#pragma once
/// \file
/// The registered scans' points in the renderer: which scans the view shows and at which
/// poses, one scan read at a time off the UI thread and uploaded over the next frames
/// (the renderer keeps the only copy). UI thread only; the read runs on its own thread.

#include <cstddef>
#include <cstdint>
#include <future>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/gui/point_renderer.hpp"

namespace anascan::field {

struct ScanChunksConfig {
    int worker_nice = 10;  ///< Nice increment of the reading thread (thread_priority.hpp).
    /// Points uploaded per frame (glBufferSubData), shuffled on the reading thread; 0:
    /// shuffled and uploaded in one frame.
    std::size_t upload_points_per_frame = 20'000;
};

class ScanChunks {
public:
    explicit ScanChunks(ScanChunksConfig config) : config_(config) {}
    /// The scans of the model's group with a pose are drawn at their poses; others removed.
    void update(const std::vector<acquisition::ScanRecord>& scans, gui::PointRenderer& renderer);
    /// Takes a finished read into the renderer, uploads a step and starts the next read;
    /// true when a read finished (the rows may have moved meanwhile: refresh them).
    bool poll(const acquisition::SessionStore* store, gui::PointRenderer& renderer);
    /// The last read's error (for the status bar), once; empty when none.
    std::string take_error() { return std::exchange(error_, {}); }
    /// Nothing to read or upload.
    bool settled() const { return !pending_ && !uploading_ && to_load_.empty(); }
    /// The last poll() copied points to the GPU (a new scan, or a step of it).
    bool uploaded_in_last_poll() const { return uploaded_in_last_poll_; }
    /// Time each uploading poll spent taking the loaded scan and copying points, ms.
    const std::vector<double>& upload_work_ms() const { return upload_work_ms_; }
    std::size_t shown() const { return shown_.size(); }

private:
    bool take_read(gui::PointRenderer& renderer);
    void start_read(const acquisition::SessionStore* store);

    ScanChunksConfig config_;
    std::map<std::int64_t, Pose> shown_;   ///< Chunks in the renderer and their poses.
    std::map<std::int64_t, Pose> wanted_;  ///< Scans the view should show, at these poses.
    std::vector<std::int64_t> to_load_;    ///< Wanted scans whose points are not shown yet.
    std::set<std::int64_t> unloadable_;    ///< Scans whose file could not be read.
    std::string error_;
    std::optional<std::future<Expected<Scan>>> pending_;
    std::int64_t loading_seq_ = -1;
    bool uploading_ = false;  ///< The renderer is still uploading a loaded scan.
    bool uploaded_in_last_poll_ = false;
    std::vector<double> upload_work_ms_;
};

}  // namespace anascan::field
