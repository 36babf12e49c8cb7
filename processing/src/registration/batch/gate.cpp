// The session RMS gate of register_scans: verified pairs fitting much worse than the
// session's typical pair are look-alikes (see ScanRegistrationConfig::session_rms_gate_factor).
#include <algorithm>
#include <limits>
#include <vector>

#include "anascan/processing/core/median.hpp"
#include "registration/batch/steps.hpp"

namespace anascan::detail {
double session_rms_gate_m(const std::vector<PairOutcome>& pairs, std::size_t scan_count,
                          const ScanRegistrationConfig& config) {
    constexpr double kOff = std::numeric_limits<double>::infinity();
    if (config.session_rms_gate_factor <= 0.0) return kOff;
    std::vector<double> best(scan_count, kOff), spacings;
    for (const PairOutcome& p : pairs) {
        if (!p.verified) continue;
        best[p.source] = std::min(best[p.source], p.global.rms_m);
        best[p.target] = std::min(best[p.target], p.global.rms_m);
        spacings.push_back(p.global.target_spacing_m);
    }
    std::erase_if(best, [](double rms) { return rms == kOff; });
    if (best.empty() || best.size() < config.min_scans_for_rms_gate) return kOff;
    return std::max(config.session_rms_gate_factor * upper_median(best),
                    config.session_rms_gate_min_spacing_fraction * upper_median(spacings));
}

bool apply_rms_gate(PairOutcome& pair, double gate_m) {
    if (!pair.verified || pair.global.rms_m <= gate_m) return false;
    pair.verified = false;
    pair.above_rms_gate = true;
    pair.weight = 0.0;
    return true;
}

}  // namespace anascan::detail
