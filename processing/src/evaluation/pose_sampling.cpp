#include "anascan/processing/evaluation/pose_sampling.hpp"

namespace anascan {

Pose sample_random_pose(std::mt19937& rng, double max_translation_m) {
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    const Eigen::Vector3d direction(normal(rng), normal(rng), normal(rng));
    return make_pose(q.normalized(), max_translation_m * unit(rng) * direction.normalized());
}

}  // namespace anascan
