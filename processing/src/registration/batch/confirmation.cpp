// The warning for placed scans whose pose no second scan confirms.
#include <string>

#include "registration/batch/steps.hpp"

namespace anascan::detail {

void warn_unconfirmed_scans(ScanRegistrationResult& result) {
    std::vector<std::size_t> links(result.scans.size(), 0);
    for (const PairOutcome& p : result.pairs) {
        if (!p.linked || p.link_dropped) continue;
        ++links[p.source];
        ++links[p.target];
    }
    if (result.placed_count < 3) return;  // Two scans: one link is all there can be.
    for (std::size_t i = 0; i < result.scans.size(); ++i) {
        ScanOutcome& scan = result.scans[i];
        if (!scan.placed || links[i] >= 2) continue;
        const std::string text =
            links[i] == 0 ? "placed by the pose graph alone: no kept link to another scan checks "
                            "its pose"
                          : "placed through one link only: no second scan confirms its pose "
                            "(a look-alike fit would go unnoticed)";
        scan.warning = scan.warning.empty() ? text : scan.warning + "; " + text;
    }
}

}  // namespace anascan::detail
