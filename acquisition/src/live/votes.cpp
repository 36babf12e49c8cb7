// Pose votes of LiveRegistrar (see live_registration_votes.hpp).
#include "live/votes.hpp"

#include <algorithm>

namespace anascan::acquisition::live {

bool poses_agree(const Pose& T_a, const Pose& T_b, const Eigen::Vector3d& at_m,
                 double max_rotation_deg, double max_displacement_m) {
    return rotation_angle_deg(T_a.inverse() * T_b) <= max_rotation_deg &&
           (T_a * at_m - T_b * at_m).norm() <= max_displacement_m;
}

void PoseVotes::add(const Pose& T, std::size_t supporter, const Eigen::Vector3d& at_m) {
    for (Cluster& c : clusters_) {
        if (poses_agree(c.T, T, c.at_m, max_rotation_deg_, max_displacement_m_)) {
            c.supporters.insert(supporter);
            return;
        }
    }
    clusters_.push_back({.T = T, .at_m = at_m, .supporters = {supporter}});
}

std::optional<Pose> PoseVotes::winner(std::size_t min_support, double ratio) const {
    const Cluster* best = nullptr;
    std::size_t runner_up = 0;
    for (const Cluster& c : clusters_) {
        if (!best || c.supporters.size() > best->supporters.size()) {
            if (best) runner_up = std::max(runner_up, best->supporters.size());
            best = &c;
        } else {
            runner_up = std::max(runner_up, c.supporters.size());
        }
    }
    if (!best || best->supporters.size() < min_support) return std::nullopt;
    if (static_cast<double>(best->supporters.size()) < ratio * static_cast<double>(runner_up)) {
        return std::nullopt;
    }
    return best->T;
}

}  // namespace anascan::acquisition::live
