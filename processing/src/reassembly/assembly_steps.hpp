#pragma once
// The steps of the constrained block assembly (block_assembly.hpp): samples of the faces,
// the linear rows of the three terms and of the non-penetration constraints.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "anascan/processing/reassembly/block_assembly.hpp"
#include "anascan/processing/spatial/kdtree.hpp"

namespace anascan::reassembly::assembly_detail {

/// A face's inliers (model frame) with a k-d tree for closest points, and its samples.
struct FacePoints {
    std::vector<Eigen::Vector3f> points;
    std::vector<Eigen::Vector3f> normals;
    std::vector<int> samples;  ///< Indices into points, evenly spread.
    std::unique_ptr<KdTree> tree;
};

/// Per block and face: the face points of every face named by a contact.
struct Prepared {
    std::vector<std::vector<FacePoints>> faces;  ///< [block][face]; empty when unused.
    std::vector<int> slot;                       ///< Unknown block slot, -1 when fixed.
    int num_slots = 0;
};

Prepared prepare(const AssemblyProblem& problem, const AssemblyConfig& config);

/// The motion parametrisation of one iteration: per slot a reference point and length.
struct Frames {
    std::vector<Eigen::Vector3d> reference_m;  ///< Per block: its centroid (world).
    std::vector<double> length_m;              ///< Per block: RMS radius (rotation scale).
};

/// One linear row nᵀ v_jk(x) (+ weight) against `rhs`; `link` names the source pair.
struct Row {
    int j = 0, k = 0;
    Eigen::Vector3d x, n;
    double rhs = 0.0;
    int link = 0;
};

/// The rows of one iteration, by term; constraints are the contact rows (>= rhs).
struct Rows {
    std::vector<Row> contact, coplanar, colinear;
};

Rows build_rows(const AssemblyProblem& problem, const Prepared& prepared,
                const std::vector<Pose>& T, const AssemblyConfig& config);

/// The dense matrix of rows (weight per row) over the 6 unknowns of every slot.
Eigen::MatrixXd row_matrix(const std::vector<Row>& rows, const Prepared& prepared,
                           const Frames& frames, double weight);

/// The motion frames at poses T: per block its centroid and RMS radius.
Frames frames_of(const AssemblyProblem& problem, const std::vector<Pose>& T);

/// The right-hand sides of rows, times `weight`.
Eigen::VectorXd rhs_of(const std::vector<Row>& rows, double weight);

/// One iteration's quadratic program, min ½ uᵀH u - gᵀu subject to C u >= d, with the
/// normal equations kept per term (for the figures tool's diagnosis of each term's pull).
struct IterationQp {
    Eigen::MatrixXd H_reg, H_cp, H_cl;
    Eigen::VectorXd g_reg, g_cp, g_cl;
    Eigen::MatrixXd C;  ///< The contact rows (empty unless constrained).
    Eigen::VectorXd d;
    Eigen::MatrixXd H() const;
    Eigen::VectorXd g() const;
};
IterationQp iteration_qp(const Rows& rows, const Prepared& prepared, const Frames& frames,
                         bool constrained);

/// The world-frame edge line of a LineRef: point and unit direction; false when absent.
bool edge_line(const AssemblyProblem& problem, const LineRef& ref, const Pose& T,
               Eigen::Vector3d& point_m, Eigen::Vector3d& direction, double& length_m);

/// Grid samples of a face's rectangle on its plane (model frame).
std::vector<Eigen::Vector3d> rectangle_samples(const PlanarFace& face, int per_side);

}  // namespace anascan::reassembly::assembly_detail
