#pragma once
// The registrar's decision as the JSON object stored with each scan (quality_json).

#include <string>
#include <string_view>

#include "anascan/acquisition/live/live_registration.hpp"

namespace anascan::acquisition {

/// {"method", "registered", "group", "rms_m", "overlap_fraction", "normal_deviation_deg",
///  "degeneracy", "time_s", "reduced_points", "message", "attempts": [{"method", "status",
///  "target_seq", "target_group", "rms_m", "overlap_fraction", "time_s"}]}.
std::string decision_json(const LiveDecision& decision);

/// {"reason": text}, for a scan that could not even be handed to the registrar.
std::string reason_json(std::string_view reason);

/// {"reason": text, "disagreement": the pair test failed}, for a scan taken out of its group.
std::string taken_out_json(const LiveTakenOut& taken_out, std::string_view reason);

}  // namespace anascan::acquisition
