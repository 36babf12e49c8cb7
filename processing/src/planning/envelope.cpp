// The working envelopes of the scanner kinds, and the plan as JSON.

#include <nlohmann/json.hpp>

#include "planning/steps.hpp"

namespace anascan {

ScannerEnvelope structured_light_envelope() { return {}; }

ScannerEnvelope terrestrial_envelope() {
    // A Riegl-like station on a tripod (the simulated sim:tof's figures): 360° around, a
    // wide vertical field, a few millimetres between points at several metres.
    return {.min_standoff_m = 2.0,
            .max_standoff_m = 4.0,
            .horizontal_fov_deg = 120.0,
            .vertical_fov_deg = 90.0,
            .spacing_at_1m_m = 0.0009,
            .min_height_m = 1.2,
            .max_height_m = 1.8,
            .max_radius_m = 6.0,
            .min_clearance_m = 1.0};
}

const char* to_string(NextViewAdvice advice) {
    switch (advice) {
        case NextViewAdvice::kScan:
            return "scan";
        case NextViewAdvice::kTurnOver:
            return "turn-over";
        case NextViewAdvice::kDone:
            return "done";
        case NextViewAdvice::kNoCoverage:
            break;
    }
    return "no-coverage";
}

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

std::string next_view_to_json(const NextView& view) {
    nlohmann::json j{{"advice", to_string(view.advice)},
                     {"hint", view.hint},
                     {"gain_percent", 100.0 * view.gain_fraction},
                     {"gain_area_m2", view.gain_area_m2},
                     {"overlap_percent", 100.0 * view.overlap_fraction},
                     {"visible_now_area_m2", view.visible_now_area_m2},
                     {"after_turn_area_m2", view.after_turn_area_m2},
                     {"candidates", view.candidates}};
    if (view.advice == NextViewAdvice::kScan) {
        j["sensor_m"] = vec(view.sensor_world_m);
        j["aim_m"] = vec(view.aim_world_m);
        j["standoff_m"] = view.standoff_m;
        j["height_m"] = view.height_m;
    }
    const Eigen::Matrix3d& R = view.frame.R_stone_world;
    j["stone_frame"] = {
        {"x", vec(R.row(0).transpose())},       {"y", vec(R.row(1).transpose())},
        {"up", vec(R.row(2).transpose())},      {"origin_m", vec(view.frame.origin_world_m)},
        {"extent_m", vec(view.frame.extent_m)}, {"ground_known", view.frame.ground_known}};
    return j.dump();
}

}  // namespace anascan
