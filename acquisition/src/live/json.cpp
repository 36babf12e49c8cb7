#include "live/json.hpp"

#include <nlohmann/json.hpp>

namespace anascan::acquisition {

std::string decision_json(const LiveDecision& d) {
    nlohmann::json attempts = nlohmann::json::array();
    for (const LiveAttempt& a : d.attempts)
        attempts.push_back({{"method", std::string(to_string(a.method))},
                            {"status", a.status},
                            {"target_seq", a.target_seq},
                            {"target_group", a.target_group},
                            {"rms_m", a.rms_m},
                            {"overlap_fraction", a.overlap_fraction},
                            {"time_s", a.time_s}});
    return nlohmann::json{{"method", std::string(to_string(d.method))},
                          {"registered", d.registered},
                          {"group", d.group},
                          {"rms_m", d.rms_m},
                          {"overlap_fraction", d.overlap_fraction},
                          {"normal_deviation_deg", d.normal_deviation_deg},
                          {"degeneracy", d.degeneracy},
                          {"time_s", d.time_s},
                          {"reduced_points", d.reduced_points},
                          {"message", d.message},
                          {"attempts", attempts}}
        .dump();
}

std::string reason_json(std::string_view reason) {
    return nlohmann::json{{"reason", std::string(reason)}}.dump();
}

std::string taken_out_json(const LiveTakenOut& taken_out, std::string_view reason) {
    return nlohmann::json{{"reason", std::string(reason)}, {"disagreement", taken_out.disagreement}}
        .dump();
}

}  // namespace anascan::acquisition
