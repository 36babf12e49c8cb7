// The dense penetration check on two boxes in contact along x: a scan hole in the second
// box's joint face by its top edge (an open mesh) reads no penetration at the true contact,
// and a real 1 mm penetration reads 1 mm without the hole and is not hidden by it (over the
// hole the mesh has no joint face: the depth read there is the distance to the top face);
// the gap of every joint-face point is kept per point (the assembly's gap colours).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "anascan/processing/reassembly/assembly_check.hpp"
#include "anascan/processing/reassembly/block_assembly.hpp"
#include "box_mesh.hpp"

namespace anascan::reassembly {
namespace {

const Eigen::Vector3d kSize{1.0, 0.6, 0.5};

// The mesh without the triangles of the face with outward normal `n` that touch the ball
// (centre, radius), and without the vertices no triangle uses any more.
Mesh with_hole(const Mesh& mesh, const Eigen::Vector3d& n, const Eigen::Vector3d& centre,
               double radius_m) {
    auto v = [&](int i) { return mesh.vertices.positions[std::size_t(i)].cast<double>(); };
    Mesh out;
    std::vector<int> index(mesh.vertices.size(), -1);
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d tn = (v(t[1]) - v(t[0])).cross(v(t[2]) - v(t[0])).normalized();
        bool near = false;
        for (int k = 0; k < 3; ++k) near = near || (v(t[k]) - centre).norm() < radius_m;
        if (near && tn.dot(n) > 0.99) continue;
        Eigen::Vector3i kept;
        for (int k = 0; k < 3; ++k) {
            int& i = index[std::size_t(t[k])];
            if (i < 0) {
                i = int(out.vertices.size());
                out.vertices.positions.push_back(mesh.vertices.positions[std::size_t(t[k])]);
            }
            kept[k] = i;
        }
        out.triangles.push_back(kept);
    }
    return out;
}

AssemblyBlock block_of(std::string id, const Mesh& mesh) {
    AssemblyBlock b{.id = std::move(id),
                    .points = {.positions = mesh.vertices.positions},
                    .triangles = mesh.triangles};
    EXPECT_TRUE(mesh_vertex_normals(mesh, b.points.normals));
    return b;
}

// Box 0 at the origin, box 1 next to it along x, `overlap_m` into box 0.
struct TwoBoxes {
    AssemblyProblem problem;
    std::vector<Pose> T;
};

TwoBoxes two_boxes(bool hole, double overlap_m) {
    const Mesh box = testing::box_mesh(kSize, 0.01);
    // The hole: 40 mm around the middle of box 1's joint-face top edge, in its model frame.
    const Mesh holed = with_hole(box, -Eigen::Vector3d::UnitX(),
                                 Eigen::Vector3d(-0.5 * kSize.x(), 0.0, 0.5 * kSize.z()), 0.04);
    TwoBoxes w;
    w.problem.blocks = {block_of("b0", box), block_of("b1", hole ? holed : box)};
    w.T = {Pose::Identity(), Pose(Eigen::Translation3d(kSize.x() - overlap_m, 0.0, 0.0))};
    return w;
}

TEST(AssemblyCheck, AHoleByTheEdgeReadsNoPenetrationAtTheTrueContact) {
    const TwoBoxes w = two_boxes(true, 0.0);
    ASSERT_LT(w.problem.blocks[1].points.size(), w.problem.blocks[0].points.size());
    const AssemblyCheck c = check_assembly(w.problem, w.T);
    EXPECT_GT(c.measured_points, 1000u);
    EXPECT_LE(c.penetration_max_m, 1e-5) << c.penetrating_points << " points";
}

TEST(AssemblyCheck, ARealPenetrationIsReadAtItsDepth) {
    const AssemblyCheck c =
        check_assembly(two_boxes(false, 0.0).problem, two_boxes(false, 0.001).T);
    EXPECT_NEAR(c.penetration_max_m, 0.001, 1e-5);
    EXPECT_GT(c.penetrating_points, 1000u);
    const AssemblyCheck holed =
        check_assembly(two_boxes(true, 0.0).problem, two_boxes(true, 0.001).T);
    EXPECT_GE(holed.penetration_max_m, 0.001 - 1e-5);
    EXPECT_GT(holed.penetrating_points, 1000u);
}

// The face of `b` whose normal is `n` (its features found from the mesh).
int face_along(const AssemblyBlock& b, const Eigen::Vector3d& n) {
    for (const PlanarFace& f : b.features.faces)
        if (f.normal.dot(n) > 0.99) return f.id;
    ADD_FAILURE() << b.id << ": no face along " << n.transpose();
    return -1;
}

TEST(AssemblyCheck, EveryJointFacePointCarriesItsGapAndNoOtherPointDoes) {
    const Mesh box = testing::box_mesh(kSize, 0.01);
    AssemblyProblem p;
    p.blocks = {assembly_block("b0", box), assembly_block("b1", box)};
    ASSERT_TRUE(p.blocks[0].features.matchable());
    const FaceRef a{0, face_along(p.blocks[0], Eigen::Vector3d::UnitX())};
    const FaceRef b{1, face_along(p.blocks[1], -Eigen::Vector3d::UnitX())};
    p.contacts = {{a, b}};
    const std::vector<Pose> T{Pose::Identity(),
                              Pose(Eigen::Translation3d(kSize.x() + 0.002, 0.0, 0.0))};
    const AssemblyCheck c = check_assembly(p, T);
    ASSERT_EQ(c.gap_m.size(), 2u);
    ASSERT_EQ(c.contacts.size(), 1u);
    EXPECT_NEAR(c.contacts[0].gap_median_m, 0.002, 1e-5);
    // Every point off the joint faces has none; on them the gap is 2 mm but at the rim,
    // where the partner's vertex normals lean over the edge.
    std::size_t with_gap = 0, at_two_mm = 0;
    for (std::size_t k = 0; k < 2; ++k) {
        const AssemblyBlock& blk = p.blocks[k];
        const int face = k == 0 ? a.face : b.face;
        for (std::size_t i = 0; i < blk.points.size(); ++i) {
            const float g = c.gap_m[k][i];
            if (blk.features.point_face[i] != face) {
                EXPECT_TRUE(std::isnan(g)) << blk.id << " point " << i;
                continue;
            }
            if (std::isnan(g)) continue;  // its nearest partner point lies past the edge
            ++with_gap;
            at_two_mm += std::abs(g - 0.002) < 1e-4;
        }
    }
    EXPECT_EQ(with_gap, c.contacts[0].points);
    EXPECT_GT(with_gap, 1000u);
    EXPECT_GT(double(at_two_mm), 0.9 * double(with_gap)) << at_two_mm << " of " << with_gap;
}

}  // namespace
}  // namespace anascan::reassembly
