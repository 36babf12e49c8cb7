#pragma once
/// \file
/// Next-best-view: where to put the scanner next so that it observes the most of the stone's
/// surface not yet observed, from the current coverage (its surface samples and their
/// states) and the scanner's working envelope, and when the rest can only be seen after
/// turning the stone over. Pure geometry; see docs/next-best-view.md for the method and the
/// figures.
///
/// Library code: no I/O, parallel loops with TBB, results independent of the thread count.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "anascan/processing/cleaning/plane_removal.hpp"
#include "anascan/processing/coverage/coverage.hpp"

namespace anascan {

/// Where a scanner can stand and what it sees well (for the coverage criterion).
struct ScannerEnvelope {
    double min_standoff_m = 0.8;  ///< Sensor to the aim point, nearest planned.
    double max_standoff_m = 1.4;  ///< Farthest planned.
    /// Field of view of the whole device (structured light: where camera and projector
    /// overlap), full angles.
    double horizontal_fov_deg = 33.0;
    double vertical_fov_deg = 25.0;
    /// Point spacing on a surface facing the sensor 1 m away, metres; it grows with the
    /// distance and decides how far a view still meets the density criterion.
    double spacing_at_1m_m = 0.00093;
    /// Sensor height above the ground the operator can reach (tripod or hand-held).
    double min_height_m = 0.25;
    double max_height_m = 1.9;
    /// Horizontal distance from the stone's centre the tent allows.
    double max_radius_m = 3.0;
    /// Sensor kept at least this far outside the stone's surface.
    double min_clearance_m = 0.3;
};

/// Envelopes of the scanner kinds anascan drives (the simulated ones' figures).
ScannerEnvelope structured_light_envelope();
/// A terrestrial station on a tripod: long range, wide field, coarser spacing.
ScannerEnvelope terrestrial_envelope();

struct NextViewConfig {
    ScannerEnvelope scanner = structured_light_envelope();
    /// The coverage criterion the plan must meet (as CoverageConfig's).
    double max_incidence_deg = 70.0;
    double min_density_per_cm2 = 10.0;
    /// Planned at a smaller incidence than the criterion's, as a margin for the operator
    /// placing the scanner by eye.
    double planning_incidence_margin_deg = 5.0;
    int azimuth_steps = 24;            ///< Directions around each aim point.
    int elevation_steps = 7;           ///< From -15° to 75° above the horizontal.
    int standoff_steps = 3;            ///< Between min and max standoff.
    std::size_t max_aim_points = 8;    ///< Largest holes aimed at (plus all unseen's centre).
    std::size_t max_samples = 6000;    ///< Unobserved samples evaluated (evenly thinned).
    double min_gain_fraction = 0.003;  ///< Below this, no view on this side is worth it.
    /// Of what a planned view observes, at least this much must be observed already, so that
    /// the new scan registers to the model (a view of only the unseen joins nothing).
    double min_overlap_fraction = 0.4;
    /// Up in the model frame when no view showed the ground: for example the mean of the
    /// scanners' image-up directions (scanners are held upright). Absent: the surface's
    /// thinnest direction.
    std::optional<Eigen::Vector3d> up_hint_world;
    /// Where the model's scans were taken from (model frame). A planned view stays within
    /// max_step_deg, seen from the stone's centre, of one of them, as an operator walks on
    /// from where they stand: the new scan then shares faces (not just one flat face) with
    /// the model. Empty: anywhere.
    std::vector<Eigen::Vector3d> scanner_positions_world;
    double max_step_deg = 45.0;
    /// Where views planned before were taken whose scans then did not join the model (model
    /// frame). No view is planned within failed_view_radius_m of one: a view that did not
    /// register is not asked for again (the coverage it promised is still missing, so the
    /// same view would win every time).
    std::vector<Eigen::Vector3d> failed_sensor_positions_world;
    double failed_view_radius_m = 0.3;
};

/// The stone's own frame for words: +z up from the ground, origin on the ground under the
/// surface's centroid, +x along the longest horizontal extent.
struct PlanningFrame {
    Eigen::Matrix3d R_stone_world = Eigen::Matrix3d::Identity();  ///< Rows: stone x, y, z.
    Eigen::Vector3d origin_world_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d extent_m = Eigen::Vector3d::Zero();  ///< Of the surface, stone axes.
    bool ground_known = false;  ///< Else +z is the surface's thinnest direction.

    Eigen::Vector3d to_stone(const Eigen::Vector3d& world_m) const {
        return R_stone_world * (world_m - origin_world_m);
    }
};

enum class NextViewAdvice {
    kScan,        ///< Scan from the proposed view.
    kTurnOver,    ///< Nothing worth scanning is left on this side: turn the stone over.
    kDone,        ///< No unobserved area is left that any view could add.
    kNoCoverage,  ///< The coverage report is not usable (no surface).
};

struct NextView {
    NextViewAdvice advice = NextViewAdvice::kNoCoverage;
    Eigen::Vector3d sensor_world_m = Eigen::Vector3d::Zero();  ///< Proposed sensor position.
    Eigen::Vector3d aim_world_m = Eigen::Vector3d::Zero();     ///< Point to aim at.
    double gain_fraction = 0.0;  ///< Expected coverage gain, of the surface's area (0..1).
    double gain_area_m2 = 0.0;
    /// Of what the view observes, the fraction observed already (registration needs it).
    double overlap_fraction = 0.0;
    /// Unobserved area some view from this side could still observe, and the area no view
    /// from this side can (the face it rests on, what lies under overhangs).
    double visible_now_area_m2 = 0.0;
    double after_turn_area_m2 = 0.0;
    double standoff_m = 0.0;     ///< Sensor to aim point.
    double height_m = 0.0;       ///< Sensor above the ground.
    std::size_t candidates = 0;  ///< Poses evaluated.
    PlanningFrame frame;
    std::string hint;  ///< In the operator's words, with the gain in percent.
};

/// The plan for the next scan from the current coverage (compute_coverage's report: its
/// samples, states, surface and ground).
NextView plan_next_view(const CoverageReport& coverage, const NextViewConfig& config);

/// The frame the hint's words use, from the report's surface and ground (or the up hint
/// when the report has no ground).
PlanningFrame planning_frame(const CoverageReport& coverage,
                             const std::optional<Eigen::Vector3d>& up_hint_world = {});

/// "scan", "turn-over", "done", "no-coverage".
const char* to_string(NextViewAdvice advice);

/// The plan as a JSON object (advice, hint, sensor_m, aim_m, gain_percent, areas in m²,
/// standoff_m, height_m, and the stone frame), for `--json` and the session store.
std::string next_view_to_json(const NextView& view);

}  // namespace anascan
