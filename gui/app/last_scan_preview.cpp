#include "last_scan_preview.hpp"

#include "future_ready.hpp"
#include "thread_priority.hpp"

namespace anascan::field {

void LastScanPreview::poll(const acquisition::SessionStore* store, gui::DevicePanelState& device) {
    if (ready(pending_)) {
        const Expected<gui::ScanPreview> preview = pending_->get();
        pending_.reset();
        if (preview) texture_.show(*preview, device);
    }
    if (pending_ || newest_seq_ <= preview_seq_ || store == nullptr) return;
    preview_seq_ = newest_seq_;
    pending_ =
        std::async(std::launch::async,
                   [store, seq = preview_seq_, n = worker_nice_]() -> Expected<gui::ScanPreview> {
                       lower_this_thread_priority(n);
                       auto scan = store->load_scan(seq);
                       if (!scan) return fail(scan.error());
                       return gui::make_scan_preview(*scan);
                   });
}

}  // namespace anascan::field
