#include "anascan/gui/field_view_state.hpp"

#include <fmt/format.h>

namespace anascan::gui {

const char* to_string(ScanRowState state) {
    switch (state) {
        case ScanRowState::kQueued:
            return "queued";
        case ScanRowState::kRegistered:
            return "ok";
        case ScanRowState::kUnjoined:
            return "unjoined";
        case ScanRowState::kFailed:
            return "FAILED";
        case ScanRowState::kExcluded:
            return "excluded";
        case ScanRowState::kFlagged:
            return "CONTRADICTS";
    }
    return "?";
}

std::optional<FailureBanner> failure_banner(const FieldViewState& state) {
    // The newest registration outcome decides: a later scan that joined the model means the
    // operator has recovered (e.g. scanned again from a closer viewpoint); one that joined
    // nothing does not.
    for (auto it = state.scans.rbegin(); it != state.scans.rend(); ++it) {
        if (it->state == ScanRowState::kRegistered) return std::nullopt;
        if (it->state != ScanRowState::kFailed) continue;
        FailureBanner banner{.kind = BannerKind::kFailed, .seq = it->seq};
        banner.message = fmt::format("Scan {} did not register{}{}", it->seq,
                                     it->message.empty() ? "" : ": ", it->message);
        banner.what_to_try =
            "Scan again from a viewpoint that overlaps the last good scan by about half "
            "(X excludes this scan). If the stone was turned over, press T first.";
        return banner;
    }
    return std::nullopt;
}

std::int64_t newest_scan(const FieldViewState& state) {
    for (auto it = state.scans.rbegin(); it != state.scans.rend(); ++it) {
        if (it->state != ScanRowState::kExcluded) return it->seq;
    }
    return -1;
}

}  // namespace anascan::gui
