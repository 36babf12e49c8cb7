#pragma once
// Pose votes: several global registrations (different target scans) agreeing on one pose
// outvote the 90°/180° look-alikes of a near-symmetric stone that a single pair accepts.
#include <cstddef>
#include <optional>
#include <set>
#include <vector>

#include "anascan/processing/core/pose.hpp"

namespace anascan::acquisition::live {

class PoseVotes {
public:
    /// Poses agree when they differ by less than these (displacement at the given point).
    PoseVotes(double max_rotation_deg, double max_displacement_m)
        : max_rotation_deg_(max_rotation_deg), max_displacement_m_(max_displacement_m) {}

    /// A verified pose from one supporter (e.g. a target scan); `at_m` is where poses are
    /// compared (a point of the moved scan, in its own frame).
    void add(const Pose& T, std::size_t supporter, const Eigen::Vector3d& at_m);
    /// The pose of the most supporters when they are at least `min_support` and at least
    /// `ratio` times the runner-up's.
    std::optional<Pose> winner(std::size_t min_support, double ratio) const;
    bool empty() const { return clusters_.empty(); }

private:
    struct Cluster {
        Pose T;
        Eigen::Vector3d at_m;
        std::set<std::size_t> supporters;
    };
    double max_rotation_deg_, max_displacement_m_;
    std::vector<Cluster> clusters_;
};

/// True when T_a and T_b agree within the limits at point `at_m`.
bool poses_agree(const Pose& T_a, const Pose& T_b, const Eigen::Vector3d& at_m,
                 double max_rotation_deg, double max_displacement_m);

}  // namespace anascan::acquisition::live
