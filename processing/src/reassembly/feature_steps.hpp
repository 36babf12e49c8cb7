#pragma once
// The steps of extract_block_features, each in its own file: faces (RANSAC, refit, merge,
// rectangle), adjacency, roughness, holes. Internal to processing/reassembly.

#include <cstddef>
#include <span>
#include <vector>

#include "anascan/processing/reassembly/block_features.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::reassembly::detail {

/// The oriented input and what every step shares.
struct FeatureInput {
    std::span<const Eigen::Vector3f> points;
    std::span<const Eigen::Vector3f> normals;
    const KdTree& tree;
    double spacing_m = 0.0;
};

/// A face being built: plane, rectangle and its inliers (indices into the input).
struct FaceBuild {
    PlanarFace face;
    std::vector<std::size_t> inliers;
};

/// RANSAC planes refitted by least squares, merged when parallel and close, with their
/// bounding rectangles; faces below the minimum area dropped. Largest first.
std::vector<FaceBuild> find_faces(const FeatureInput& in, const FaceDetectionConfig& config);

/// Both directed edges of every pair of faces that meet along a shared segment.
std::vector<FaceEdge> face_adjacency(const FeatureInput& in, const std::vector<FaceBuild>& faces,
                                     const AdjacencyConfig& config);

/// Moves each rectangle side that ends at a neighbouring face onto that face's plane (the
/// dressed size, not the extent of the inliers, which stop short of rounded or chipped
/// edges), and recomputes width, height, area and centre.
void snap_to_neighbours(std::vector<FaceBuild>& faces, const std::vector<FaceEdge>& edges,
                        double max_shift_m);

/// ρ of every face (paper §5.1): the mean over samples p of the mean of e_k over the ball.
void face_roughness(const FeatureInput& in, const std::vector<int>& point_face,
                    std::vector<FaceBuild>& faces, const RoughnessConfig& config);

/// Holes below every face: clusters of floor points deeper than the minimum depth.
void face_holes(const FeatureInput& in, std::vector<FaceBuild>& faces, const HoleConfig& config);

/// In-plane coordinates of p along the face's (width, height) axes from its centre.
Eigen::Vector2d face_uv(const PlanarFace& face, const Eigen::Vector3d& p);

}  // namespace anascan::reassembly::detail
