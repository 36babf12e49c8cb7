#pragma once
// Random Gaussian bumps for the synthetic height fields of the registration tests: a
// non-symmetric surface that features and fine registration can lock onto.
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"

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

// Height field z = Σ h exp(−|xy − c|² / 2w²) over x in [x_min, x_max], |y| <= 0.1, on a
// grid of `spacing_m` shifted by `offset_m`; normals up (solid below), analytic.
inline PointCloud bumpy_surface(const std::vector<Bump>& bumps, double x_min, double x_max,
                                double spacing_m, double offset_m) {
    PointCloud cloud;
    for (double x = x_min + offset_m; x <= x_max; x += spacing_m) {
        for (double y = -0.1 + offset_m; y <= 0.1; y += spacing_m) {
            double z = 0.0;
            Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
            for (const Bump& b : bumps) {
                const Eigen::Vector2d d = Eigen::Vector2d(x, y) - b.centre_m;
                const double g =
                    b.height_m * std::exp(-d.squaredNorm() / (2 * b.width_m * b.width_m));
                z += g;
                gradient -= g * d / (b.width_m * b.width_m);
            }
            cloud.positions.emplace_back(float(x), float(y), float(z));
            cloud.normals.push_back(
                Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized().cast<float>());
        }
    }
    return cloud;
}

}  // namespace anascan::testing_util
