// The plan in the operator's words, in the stone's frame: where to stand (which end, side or
// corner, how far, how high), where to aim (which face, which part), and what it adds.

#include <cmath>
#include <cstdio>

#include "planning/steps.hpp"

namespace anascan::planning_detail {
namespace {

std::string signed_axis(char axis, double value) {
    return std::string(value < 0.0 ? "-" : "+") + axis;
}

// Ends are the faces across the longest extent, sides the others (a square block has sides).
std::string side_word(const PlanningFrame& frame, char axis) {
    const bool elongated = frame.extent_m.x() > 1.2 * frame.extent_m.y();
    return elongated && axis == 'x' ? "end" : "side";
}

std::string where_to_stand(const PlanningFrame& frame, const Eigen::Vector3d& sensor_stone) {
    const double dx = std::abs(sensor_stone.x()) - 0.5 * frame.extent_m.x();
    const double dy = std::abs(sensor_stone.y()) - 0.5 * frame.extent_m.y();
    const std::string ax = signed_axis('x', sensor_stone.x()),
                      ay = signed_axis('y', sensor_stone.y());
    if (dx <= 0.0 && dy <= 0.0) return "above the stone";
    if (dx > 0.0 && dy > 0.0 && std::min(dx, dy) > 0.5 * std::max(dx, dy))
        return "at the " + ax + "/" + ay + " corner of the stone";
    return dx > dy ? "at the " + ax + " " + side_word(frame, 'x') + " of the stone"
                   : "at the " + ay + " " + side_word(frame, 'y') + " of the stone";
}

std::string face_name(const PlanningFrame& frame, const Eigen::Vector3d& normal_stone) {
    if (normal_stone.z() > 0.7) return "the top";
    if (normal_stone.z() < -0.7) return "the underside";
    const bool along_x = std::abs(normal_stone.x()) >= std::abs(normal_stone.y());
    return along_x
               ? "the " + signed_axis('x', normal_stone.x()) + " " + side_word(frame, 'x') + " face"
               : "the " + signed_axis('y', normal_stone.y()) + " " + side_word(frame, 'y') +
                     " face";
}

std::string part_of_face(const PlanningFrame& frame, const Eigen::Vector3d& aim_stone,
                         const Eigen::Vector3d& normal_stone) {
    if (std::abs(normal_stone.z()) > 0.7 || frame.extent_m.z() <= 0.0) return "";
    const double level = aim_stone.z() / frame.extent_m.z();
    if (level < 1.0 / 3.0) return "the lower part of ";
    if (level > 2.0 / 3.0) return "the upper edge of ";
    return "the middle of ";
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
    char text[160];
    std::snprintf(text, sizeof text, pattern, a, b, c);
    return text;
}

}  // namespace

std::string hint_text(const NextView& view, const Eigen::Vector3d& aimed_normal_world) {
    const PlanningFrame& frame = view.frame;
    switch (view.advice) {
        case NextViewAdvice::kScan: {
            const Eigen::Vector3d sensor = frame.to_stone(view.sensor_world_m);
            const Eigen::Vector3d aim = frame.to_stone(view.aim_world_m);
            const Eigen::Vector3d n = frame.R_stone_world * aimed_normal_world;
            std::string hint =
                where_to_stand(frame, sensor) +
                format(", %.1f m from the aim point, scanner about %.1f m ", view.standoff_m,
                       view.height_m) +
                (frame.ground_known ? "above the ground" : "above the stone's lowest point") +
                "; aim at " + part_of_face(frame, aim, n) + face_name(frame, n) +
                format(": +%.1f %% coverage", 100.0 * view.gain_fraction);
            if (view.after_turn_area_m2 > 0.0)
                hint += format(" (%.0f cm² can only be seen after turning the stone over)",
                               view.after_turn_area_m2 * 1e4);
            return hint;
        }
        case NextViewAdvice::kTurnOver:
            return format(
                "turn the stone over: nothing worth a scan is left on this side; "
                "%.0f cm² (the face it rests on and what faces the ground) can only "
                "be seen after the turn",
                view.after_turn_area_m2 * 1e4);
        case NextViewAdvice::kDone:
            return format(
                "nothing left that a scan could add (%.0f cm² unobserved, out of "
                "any view's reach)",
                (view.visible_now_area_m2 + view.after_turn_area_m2) * 1e4);
        case NextViewAdvice::kNoCoverage:
            break;
    }
    return "no coverage yet: scan the stone first";
}

}  // namespace anascan::planning_detail
