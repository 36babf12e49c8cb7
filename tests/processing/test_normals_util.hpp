#pragma once
/// \file
/// Test-only normal estimation (a stand-in until processing has its own): local PCA over
/// the k nearest neighbours, oriented toward a viewing direction.
///
/// Orientation of the Stanford bunny scans: the Cyberware scanner sits on the +z side of
/// each scan frame. Checked on bun000: with normals oriented to +z, 91% point away from
/// the centroid of bun000 ∪ bun180 (the closed bunny), and bun000's points lie on the +z
/// side of that centroid.

#include <Eigen/Eigenvalues>
#include <cstddef>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::test {

/// Fills `cloud.normals` with the smallest-eigenvalue eigenvector of the covariance of each
/// point's k nearest neighbours (cloud's local frame), flipped so that n·toward >= 0.
/// Points with fewer than 3 neighbours or a non-finite position get a NaN normal.
inline void estimate_normals_pca(PointCloud& cloud, const Eigen::Vector3f& toward,
                                 std::size_t k = 16) {
    const KdTree tree(cloud.positions);
    std::vector<Neighbor> neighbors;
    cloud.normals.assign(cloud.size(), Eigen::Vector3f::Constant(std::nanf("")));
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!cloud.positions[i].allFinite()) continue;
        tree.knn(cloud.positions[i], k, neighbors);
        if (neighbors.size() < 3) continue;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (const Neighbor& nb : neighbors) mean += cloud.positions[nb.index].cast<double>();
        mean /= static_cast<double>(neighbors.size());
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const Neighbor& nb : neighbors) {
            const Eigen::Vector3d d = cloud.positions[nb.index].cast<double>() - mean;
            cov += d * d.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(cov);
        Eigen::Vector3f n = eigen.eigenvectors().col(0).cast<float>();
        if (n.dot(toward) < 0.0f) n = -n;
        cloud.normals[i] = n;
    }
}

}  // namespace anascan::test
