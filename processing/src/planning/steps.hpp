#pragma once
// Internal steps of next_best_view.cpp (not installed).

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/planning/next_best_view.hpp"

namespace anascan::planning_detail {

/// A surface sample the plan wants observed (unobserved or sparse), world frame.
struct WantedSample {
    Eigen::Vector3d position_m;
    Eigen::Vector3d normal;
};

/// The samples not yet observed, evenly thinned to at most max_samples; `area_per_sample_m2`
/// is the area each kept one stands for.
struct WantedSamples {
    std::vector<WantedSample> samples;
    double area_per_sample_m2 = 0.0;
    double total_area_m2 = 0.0;  ///< Of all unobserved and sparse samples.
    /// The samples observed already, thinned alike, for the overlap a view keeps.
    std::vector<WantedSample> observed;
    double area_per_observed_m2 = 0.0;
};
WantedSamples wanted_samples(const CoverageReport& coverage, std::size_t max_samples);

/// A scanner pose to evaluate: where it stands and what it aims at.
struct Candidate {
    Eigen::Vector3d sensor_m;
    Eigen::Vector3d aim_m;
    double standoff_m = 0.0;
    double height_m = 0.0;  ///< Above the ground (or the lowest surface point).
};

/// Sensor poses around the aim points (largest holes, centre of what is unseen) within the
/// envelope: height range, tent radius, outside the stone by the clearance.
std::vector<Candidate> candidate_views(const CoverageReport& coverage, const WantedSamples& wanted,
                                       const PlanningFrame& frame, const NextViewConfig& config);

/// Height of a world point above the frame's ground.
inline double height_above_ground(const PlanningFrame& frame, const Eigen::Vector3d& world_m) {
    return frame.to_stone(world_m).z();
}

/// What a candidate would observe well (field of view, incidence, density; a convex
/// surface occludes nothing that faces the sensor).
class ViewModel {
public:
    ViewModel(const Candidate& candidate, const Eigen::Vector3d& up, const NextViewConfig& config);
    bool observes(const WantedSample& sample) const;
    bool valid() const { return valid_; }

private:
    Eigen::Vector3d sensor_, x_, y_, z_;
    double tan_half_h_ = 0.0, tan_half_v_ = 0.0, cos_max_incidence_ = 0.0;
    double max_distance_sq_ = 0.0;  ///< Beyond it the density falls under the criterion.
    double density_factor_ = 0.0;   ///< cos(incidence) / distance² above it: dense enough.
    bool valid_ = false;
};

/// Indices of the samples the candidate observes.
std::vector<std::size_t> observed_by(const Candidate& candidate, const WantedSamples& wanted,
                                     const Eigen::Vector3d& up, const NextViewConfig& config);

/// What a candidate observes well: wanted area (the gain) and area observed already.
struct ViewScore {
    double gain_m2 = 0.0;
    double overlap_m2 = 0.0;
    double overlap_fraction() const {
        return gain_m2 + overlap_m2 > 0.0 ? overlap_m2 / (gain_m2 + overlap_m2) : 0.0;
    }
};
ViewScore score_view(const Candidate& candidate, const WantedSamples& samples,
                     const Eigen::Vector3d& up, const NextViewConfig& config);

/// Per sample: whether any candidate observes it.
std::vector<bool> observable_by_any(std::span<const Candidate> candidates,
                                    const WantedSamples& wanted, const Eigen::Vector3d& up,
                                    const NextViewConfig& config);

/// The hint in the operator's words.
std::string hint_text(const NextView& view, const Eigen::Vector3d& aimed_normal_world);

}  // namespace anascan::planning_detail
