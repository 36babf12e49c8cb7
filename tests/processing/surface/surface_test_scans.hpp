#pragma once
// Synthetic scans of a sphere: each scan holds the points its sensor sees (facing it),
// with seeded noise, and nothing else (no normals). Shared by the surface tests.
#include <cmath>
#include <random>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/surface/reconstruction.hpp"

namespace anascan::test {

struct SphereScans {
    double radius_m = 0.05;
    std::vector<PointCloud> clouds;
    std::vector<Eigen::Vector3d> sensors;

    std::vector<PlacedScan> placed(bool with_sensors = true) const {
        std::vector<PlacedScan> out;
        for (std::size_t i = 0; i < clouds.size(); ++i) {
            out.push_back({&clouds[i], with_sensors ? std::optional(sensors[i]) : std::nullopt});
        }
        return out;
    }
};

/// Scans from sensors at `distance_m` in the given directions; points every ~`spacing_m`.
inline SphereScans scan_sphere(const std::vector<Eigen::Vector3d>& directions, double spacing_m,
                               double noise_m, unsigned seed) {
    SphereScans s;
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double area = 4.0 * M_PI * s.radius_m * s.radius_m;
    const auto n = static_cast<std::size_t>(area / (spacing_m * spacing_m));
    for (const Eigen::Vector3d& dir : directions) {
        const Eigen::Vector3d sensor = 0.4 * dir.normalized();
        PointCloud cloud;
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector3d u =
                Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
            const Eigen::Vector3d p = s.radius_m * u;
            if (u.dot((sensor - p).normalized()) < 0.25) continue;  // grazing or hidden
            cloud.positions.push_back((p + noise_m * gauss(rng) * u).cast<float>());
        }
        s.clouds.push_back(std::move(cloud));
        s.sensors.push_back(sensor);
    }
    return s;
}

/// Six sensors around the sphere: every part is seen.
inline std::vector<Eigen::Vector3d> all_round() {
    return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
}

/// Five sensors above the equator: the bottom cap (z < -0.5 r) is never seen.
inline std::vector<Eigen::Vector3d> from_above() {
    return {{1, 0, 1.2}, {-1, 0, 1.2}, {0, 1, 1.2}, {0, -1, 1.2}, {0, 0, 1}};
}

}  // namespace anascan::test
