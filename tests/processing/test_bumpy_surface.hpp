#pragma once
// Random Gaussian bumps for the synthetic height fields of the registration tests: a
// non-symmetric surface that features and fine registration can lock onto.
#include <Eigen/Core>
#include <random>
#include <vector>

namespace anascan::testing_util {

struct Bump {
    Eigen::Vector2d centre_m;
    double height_m;
    double width_m;
};

inline std::vector<Bump> random_bumps(unsigned seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> where(-0.1, 0.1), height(0.003, 0.012),
        width(0.006, 0.016), sign(-1.0, 1.0);
    std::vector<Bump> bumps;
    for (int i = 0; i < count; ++i) {
        const double h = height(rng) * (sign(rng) < -0.3 ? -1.0 : 1.0);
        bumps.push_back({{where(rng), where(rng)}, h, width(rng)});
    }
    return bumps;
}

}  // namespace anascan::testing_util
