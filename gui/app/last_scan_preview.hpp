#pragma once
/// \file
/// The device panel's picture of the newest scan as the scanner saw it: read and projected
/// off the UI thread (its points are freed there), uploaded on the UI thread. A newer scan
/// waits for the read in progress.

#include <cstdint>
#include <future>
#include <optional>

#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/gui/field_view_state.hpp"
#include "anascan/gui/scan_preview.hpp"
#include "preview_texture.hpp"

namespace anascan::field {

class LastScanPreview {
public:
    explicit LastScanPreview(int worker_nice) : worker_nice_(worker_nice) {}
    /// A scan the session holds (the newest is previewed).
    void saw_scan(std::int64_t seq) { newest_seq_ = std::max(newest_seq_, seq); }
    void poll(const acquisition::SessionStore* store, gui::DevicePanelState& device);
    /// The newest scan is shown (or nothing to show), no read pending.
    bool settled() const { return !pending_ && newest_seq_ <= preview_seq_; }

private:
    int worker_nice_ = 10;
    std::int64_t newest_seq_ = -1;   ///< The newest scan in the session.
    std::int64_t preview_seq_ = -1;  ///< The scan previewed (or being read for it).
    PreviewTexture texture_;
    std::optional<std::future<Expected<gui::ScanPreview>>> pending_;
};

}  // namespace anascan::field
