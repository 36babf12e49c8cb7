#include "scan_chunks.hpp"

#include <chrono>

#include "anascan/gui/session_view.hpp"
#include "future_ready.hpp"
#include "thread_priority.hpp"

namespace anascan::field {

void ScanChunks::update(const std::vector<acquisition::ScanRecord>& scans,
                        gui::PointRenderer& renderer) {
    const int group = gui::model_group(scans);
    wanted_.clear();
    for (const auto& record : scans)
        if (gui::drawn_in_view(record, group)) wanted_.emplace(record.seq, *record.pose);
    for (auto it = shown_.begin(); it != shown_.end();) {
        const auto w = wanted_.find(it->first);
        if (w == wanted_.end()) {
            renderer.remove_chunk(it->first);
            it = shown_.erase(it);
            continue;
        }
        if (!w->second.isApprox(it->second, 1e-12)) {
            renderer.set_pose(it->first, w->second);
            it->second = w->second;
        }
        ++it;
    }
    to_load_.clear();
    for (const auto& [seq, pose] : wanted_)
        if (!shown_.contains(seq) && seq != loading_seq_ && !unloadable_.contains(seq))
            to_load_.push_back(seq);
}

/// The finished read goes to the renderer: shuffled on the reading thread, uploaded over
/// the next frames (20 000 points a frame are 240 kB of positions and 60 kB of colours).
bool ScanChunks::take_read(gui::PointRenderer& renderer) {
    Expected<Scan> scan = pending_->get();
    pending_.reset();
    const std::int64_t seq = std::exchange(loading_seq_, -1);
    const auto wanted = wanted_.find(seq);
    if (scan && wanted != wanted_.end()) {
        const std::size_t step = config_.upload_points_per_frame;
        renderer.add_chunk(seq, std::move(scan->cloud), wanted->second,
                           {.shuffled = step > 0, .points_per_step = step});
        uploaded_in_last_poll_ = true;
        shown_[seq] = wanted->second;
    } else if (!scan) {
        error_ = scan.error().message;
        unloadable_.insert(seq);
    }
    return true;
}

void ScanChunks::start_read(const acquisition::SessionStore* store) {
    loading_seq_ = to_load_.front();
    to_load_.erase(to_load_.begin());
    pending_ = std::async(std::launch::async, [store, seq = loading_seq_, n = config_.worker_nice,
                                               shuffle = config_.upload_points_per_frame > 0] {
        lower_this_thread_priority(n);
        auto scan = store->load_scan(seq);
        if (scan && shuffle) gui::shuffle_chunk_points(scan->cloud, seq);
        return scan;
    });
}

bool ScanChunks::poll(const acquisition::SessionStore* store, gui::PointRenderer& renderer) {
    uploaded_in_last_poll_ = uploading_;  // a step below
    const auto started = std::chrono::steady_clock::now();
    const bool read = ready(pending_) && take_read(renderer);
    uploading_ = renderer.upload_step();
    if (uploaded_in_last_poll_)
        upload_work_ms_.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
                .count());
    // One scan's points in CPU memory at a time: the next is read once this one is uploaded.
    if (!pending_ && !uploading_ && !to_load_.empty() && store != nullptr) start_read(store);
    return read;
}

}  // namespace anascan::field
