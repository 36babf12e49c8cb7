#pragma once
/// \file
/// Block features (method paper §5.1): the planar faces of a stone block found by RANSAC
/// (Schnabel et al. 2007, CGAL Shape_detection), the directed face-adjacency graph, per
/// face the fitted plane, width, height, area and roughness ρ (mean bending energy e_k
/// over a ball, k = 50), and the holes below each face (clamp channels, round dowels).
///
/// Input: a mesh (its vertices with area-weighted triangle normals) or a dense oriented
/// point cloud, in any frame (the block's model frame). Pure geometry: no I/O, no logging;
/// deterministic for a given config (the RANSAC draws are seeded).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "anascan/processing/core/mesh.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::reassembly {

enum class HoleKind { kClampChannel, kDowel };

/// A cluster of points well below a face's plane with floors parallel to it.
struct FaceHole {
    HoleKind kind = HoleKind::kDowel;
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();   ///< On the face plane, model frame.
    Eigen::Vector2d face_uv_m = Eigen::Vector2d::Zero();  ///< Along (width, height) axes.
    double length_m = 0.0;                                ///< Longer extent in the face.
    double width_m = 0.0;                                 ///< Shorter extent in the face.
    double depth_m = 0.0;                                 ///< Deepest floor point below the plane.
};

/// A planar face: plane n·x = offset_m with n outward, and its bounding rectangle.
struct PlanarFace {
    int id = 0;
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();       ///< Outward unit normal.
    double offset_m = 0.0;                                   ///< n·x on the plane.
    Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();      ///< Rectangle centre, on the plane.
    Eigen::Vector3d width_axis = Eigen::Vector3d::UnitX();   ///< In-plane, along the width.
    Eigen::Vector3d height_axis = Eigen::Vector3d::UnitY();  ///< normal x width_axis.
    double width_m = 0.0;                                    ///< Longer side of the rectangle.
    double height_m = 0.0;                                   ///< Shorter side.
    double area_m2 = 0.0;           ///< width * height, as the paper's w·h.
    double roughness_per_m2 = 0.0;  ///< ρ: mean of e_k over balls (1/m²).
    double rms_m = 0.0;             ///< RMS distance of the inliers to the plane.
    std::size_t num_points = 0;     ///< Inliers.
    std::vector<FaceHole> holes;
};

/// A directed edge e_ij of the face-adjacency graph: faces i and j meet along a line.
struct FaceEdge {
    int from = 0, to = 0;
    Eigen::Vector3d point_m = Eigen::Vector3d::Zero();     ///< Middle of the shared segment.
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< from.normal x to.normal, unit.
    double length_m = 0.0;                                 ///< Length of the shared segment.
    double angle_deg = 0.0;                                ///< Angle between the two normals.
};

enum class BlockStatus {
    kOk,
    kEmpty,         ///< No points (or an empty mesh).
    kNoNormals,     ///< A cloud without normals: estimate and orient them first.
    kBadMesh,       ///< A triangle names a vertex the mesh does not have.
    kNonManifold,   ///< A mesh edge shared by more than two triangles (features still found).
    kNoPlanarFace,  ///< Nothing planar of the minimum area (a column drum, a capital).
    kTooFewFaces,   ///< One face only: nothing to match it by.
    kTooNoisy,      ///< The faces' RMS exceeds the RANSAC tolerance: noise or bad normals.
};

/// A block's features. `faces` and `edges` are empty unless the status allows matching.
struct BlockFeatures {
    BlockStatus status = BlockStatus::kOk;
    std::string message;  ///< What was found or why not, for the user.
    std::vector<PlanarFace> faces;
    std::vector<FaceEdge> edges;  ///< Both directions of every adjacency.
    std::size_t num_points = 0;
    double spacing_m = 0.0;       ///< Median nearest-neighbour spacing of the input.
    std::vector<int> point_face;  ///< Per input point: face id or -1.

    bool matchable() const {
        return (status == BlockStatus::kOk || status == BlockStatus::kNonManifold) &&
               faces.size() >= 2;
    }
    /// Neighbouring face ids of a face (the targets of its outgoing edges).
    std::vector<int> neighbours(int face) const;
};

struct FaceDetectionConfig {
    double epsilon_m = 0.004;                ///< RANSAC inlier distance to the plane.
    double normal_threshold_deg = 25.0;      ///< Inlier normal deviation (CGAL's 0.9 cosine).
    double min_face_area_m2 = 0.02;          ///< Smaller faces are not reported.
    double probability = 0.01;               ///< CGAL search endurance (lower: more thorough).
    double merge_angle_deg = 3.0;            ///< Parallel planes within this and merge_offset_m
    double merge_offset_m = 0.03;            ///< of each other are one face (recess, band).
    std::size_t max_ransac_points = 300000;  ///< Larger inputs are subsampled for RANSAC.
    /// A face whose normals turn by more than strip_turn_deg between its first and last
    /// thirds, and whose middle bends off its sides by at least strip_bend_agreement of
    /// what a surface turning that much would, is a strip of a curved surface and is not
    /// reported.
    double strip_turn_deg = 5.0;
    double strip_bend_agreement = 0.5;
    std::uint64_t seed = 1;
};

struct RoughnessConfig {
    int k_neighbors = 50;        ///< k of the bending energy e_k (paper: 50).
    double radius_factor = 4.0;  ///< Ball radius r of ρ(p), in sample spacings.
    int samples_per_face = 400;  ///< Points p of each face where ρ(p) is averaged.
};

struct AdjacencyConfig {
    double band_m = 0.05;             ///< Inliers this close to the planes' line count.
    double min_edge_length_m = 0.05;  ///< Shorter shared segments are no adjacency.
    double min_angle_deg = 30.0;      ///< Flatter meetings are not an edge.
};

struct HoleConfig {
    double min_depth_m = 0.015;  ///< Below tool marks, anathyrosis and ornament background.
    double max_depth_m = 0.15;
    double floor_cos = 0.8;     ///< Floor points face the same way as the face.
    double min_area_m2 = 3e-4;  ///< Smaller clusters are noise.
    double clamp_aspect = 2.0;  ///< Longer than this times wider: a clamp channel.
};

struct BlockFeatureConfig {
    FaceDetectionConfig faces;
    RoughnessConfig roughness;
    AdjacencyConfig adjacency;
    HoleConfig holes;
    double max_rms_factor = 1.0;  ///< kTooNoisy when the median face RMS > this * epsilon.
};

/// Features of an oriented cloud (normals required, outward).
BlockFeatures extract_block_features(const PointCloud& cloud, const BlockFeatureConfig& config);

/// Features of a mesh: its vertices with area-weighted triangle normals (triangles counter-
/// clockwise from outside). An empty mesh gives kEmpty; a non-manifold one kNonManifold.
BlockFeatures extract_block_features(const Mesh& mesh, const BlockFeatureConfig& config);

/// Area-weighted triangle normals at the vertices (unit, zero for unused vertices); false
/// when an edge is shared by more than two triangles.
bool mesh_vertex_normals(const Mesh& mesh, std::vector<Eigen::Vector3f>& normals);

/// Short English name of a status ("ok", "no planar face", ...).
const char* to_string(BlockStatus status);
const char* to_string(HoleKind kind);

}  // namespace anascan::reassembly
