// Face matching on block features written out by hand: boxes whose faces, edges and holes
// are exact, so that each rule of the score is seen alone.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>

#include "anascan/processing/reassembly/face_matching.hpp"

namespace anascan::reassembly {
namespace {

// Face ids of box_features: +x, -x, +y (façade), -y (back), +z (top), -z (bottom).
enum BoxFace { kPosX, kNegX, kFacade, kBack, kTop, kBottom };

Eigen::Vector3d axis_normal(int face) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
    return n;
}

Eigen::Matrix3d yaw(double deg) {
    return Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()).matrix();
}

// The features of a box of `size` (centred, block frame) turned by `yaw_deg` about z:
// six faces with the finishes of a wall block (smooth façade, rough back, pointed beds
// and joints) and the twelve adjacencies in both directions.
BlockFeatures box_features(const Eigen::Vector3d& size, double yaw_deg) {
    const Eigen::Matrix3d R = yaw(yaw_deg);
    const double roughness[6] = {20.0, 20.0, 1.0, 150.0, 20.0, 20.0};
    BlockFeatures b;
    for (int f = 0; f < 6; ++f) {
        const Eigen::Vector3d n = axis_normal(f);
        const int u = (f / 2 + 1) % 3, v = (f / 2 + 2) % 3;
        const int wide = size[u] >= size[v] ? u : v, narrow = wide == u ? v : u;
        PlanarFace face;
        face.id = f;
        face.normal = R * n;
        face.centre_m = R * (0.5 * size[f / 2] * n);
        face.offset_m = face.normal.dot(face.centre_m);
        face.width_axis = R * Eigen::Vector3d::Unit(wide);
        face.height_axis = face.normal.cross(face.width_axis);
        face.width_m = size[wide];
        face.height_m = size[narrow];
        face.area_m2 = face.width_m * face.height_m;
        face.roughness_per_m2 = roughness[f];
        b.faces.push_back(face);
    }
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            if (i / 2 == j / 2) continue;
            const Eigen::Vector3d ni = axis_normal(i), nj = axis_normal(j);
            const Eigen::Vector3d d = ni.cross(nj);
            FaceEdge e{.from = i, .to = j};
            e.point_m = R * (0.5 * size[i / 2] * ni + 0.5 * size[j / 2] * nj);
            e.direction = R * d;
            int along = 0;
            d.cwiseAbs().maxCoeff(&along);
            e.length_m = size[along];
            e.angle_deg = 90.0;
            b.edges.push_back(e);
        }
    return b;
}

// A clamp half in the top face, `from_edge_m` in from the edge with the joint face
// `edge_face` (+x or -x), at y = y_m (block frame, before the yaw).
void add_clamp_half(BlockFeatures& b, int edge_face, double y_m, double from_edge_m,
                    double half_length_m, double yaw_deg) {
    const Eigen::Matrix3d R = yaw(yaw_deg);
    const PlanarFace& joint = b.faces[edge_face];
    const double x_edge = (R.transpose() * joint.centre_m).x();
    const double top_z = (R.transpose() * b.faces[kTop].centre_m).z();
    FaceHole h;
    h.kind = HoleKind::kClampChannel;
    h.centre_m = R * Eigen::Vector3d(x_edge - std::copysign(from_edge_m, x_edge), y_m, top_z);
    h.length_m = half_length_m;
    h.width_m = 0.015;
    h.depth_m = 0.05;
    b.faces[kTop].holes.push_back(h);
}

const Eigen::Vector3d kBlock(1.0, 0.6, 0.55);

double check(const FacePairScore& s, Check c) { return s.checks[static_cast<int>(c)]; }

TEST(FaceMatching, ClampHalvesAtTheSamePlaceAlongTheJointAgree) {
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 70.0);
    add_clamp_half(a, kPosX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(b, kNegX, 0.12, 0.04, 0.07, 70.0);
    const FacePairScore s = score_face_pair(a, kPosX, b, kNegX, {});
    EXPECT_GT(check(s, Check::kHoles), 0.9);
    EXPECT_DOUBLE_EQ(check(s, Check::kNeighbourCount), 1.0);
    EXPECT_GT(check(s, Check::kNeighbourRoughness), 0.99);

    // 40 mm apart along the joint: another clamp, not this one.
    BlockFeatures c = box_features(kBlock, 70.0);
    add_clamp_half(c, kNegX, 0.08, 0.04, 0.07, 70.0);
    EXPECT_DOUBLE_EQ(check(score_face_pair(a, kPosX, c, kNegX, {}), Check::kHoles), 0.0);
}

TEST(FaceMatching, ADowelNearTheJointIsNoHalfOfIt) {
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 0.0);
    add_clamp_half(a, kPosX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(b, kNegX, 0.12, 0.04, 0.07, 0.0);
    // A dowel of the bed joint above, 0.15 m in from b's joint edge: it stops short of
    // the edge and has no partner across this joint.
    FaceHole dowel{.kind = HoleKind::kDowel, .length_m = 0.03, .width_m = 0.03, .depth_m = 0.05};
    dowel.centre_m = Eigen::Vector3d(-0.35, -0.05, 0.275);
    b.faces[kTop].holes.push_back(dowel);
    EXPECT_GT(check(score_face_pair(a, kPosX, b, kNegX, {}), Check::kHoles), 0.9);
}

TEST(FaceMatching, AChippedEdgeDoesNotMoveTheClampAlongTheJoint) {
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 0.0);
    add_clamp_half(a, kPosX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(b, kNegX, 0.12, 0.04, 0.07, 0.0);
    // A lost corner: the shared segment of b's joint face and top covers 0.35 m of 0.6 m,
    // its middle 0.125 m off the face's.
    for (FaceEdge& e : b.edges)
        if ((e.from == kNegX && e.to == kTop) || (e.from == kTop && e.to == kNegX))
            e.length_m = 0.35, e.point_m += 0.125 * e.direction;
    EXPECT_GT(check(score_face_pair(a, kPosX, b, kNegX, {}), Check::kHoles), 0.9);
}

TEST(FaceMatching, AFacadeDoesNotMeetABackForAClampThatWouldAgree) {
    // c's +x face against a's +x face fits only with c upside down (façade to façade) or
    // with its façade against a's back. Its clamp at y = -0.12 agrees with a's at +0.12
    // only in the second placement; the finishes choose the first, where it is no clamp.
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 0.0),
                  c = box_features(kBlock, 0.0);
    add_clamp_half(a, kPosX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(b, kNegX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(c, kPosX, -0.12, 0.04, 0.07, 0.0);
    const FacePairScore wrong = score_face_pair(a, kPosX, c, kPosX, {});
    EXPECT_DOUBLE_EQ(check(wrong, Check::kHoles), 0.0);
    int facade_pairs = 0;
    for (const auto& [fa, fc] : wrong.neighbour_pairs)
        if (fa == kFacade) {
            EXPECT_EQ(fc, kFacade);
            ++facade_pairs;
        }
    EXPECT_EQ(facade_pairs, 1);
    EXPECT_GT(score_face_pair(a, kPosX, b, kNegX, {}).score, wrong.score + 2.0);
}

TEST(FaceMatching, AnExtraFaceOnOneBlockLeavesTheOtherNeighboursPaired) {
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 0.0);
    add_clamp_half(a, kPosX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(b, kNegX, 0.12, 0.04, 0.07, 0.0);
    // A broken corner between b's joint face and its façade: a sixth neighbour at 45°.
    PlanarFace chamfer = b.faces[kFacade];
    chamfer.id = 6;
    chamfer.normal = Eigen::Vector3d(-1.0, 1.0, 0.0).normalized();
    chamfer.roughness_per_m2 = 400.0;
    b.faces.push_back(chamfer);
    FaceEdge e{.from = kNegX, .to = 6, .direction = Eigen::Vector3d::UnitZ()};
    e.point_m = Eigen::Vector3d(-0.5, 0.28, 0.0), e.length_m = 0.55, e.angle_deg = 45.0;
    b.edges.push_back(e);
    const FacePairScore s = score_face_pair(a, kPosX, b, kNegX, {});
    EXPECT_DOUBLE_EQ(check(s, Check::kNeighbourCount), 0.8);  // 4 of 5 neighbours.
    EXPECT_EQ(s.neighbour_pairs.size(), 4u);
    EXPECT_GT(check(s, Check::kHoles), 0.9);
}

TEST(FaceMatching, RoughnessTellsFinishesApartNotBlocks) {
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 0.0);
    b.faces[kNegX].roughness_per_m2 = 12.0;  // Another mason's pointed finish: 20 against 12.
    EXPECT_GT(check(score_face_pair(a, kPosX, b, kNegX, {}), Check::kRoughness), 0.6);
    EXPECT_DOUBLE_EQ(check(score_face_pair(a, kPosX, b, kFacade, {}), Check::kRoughness), 0.0);
}

TEST(FaceMatching, SizesCompareAlongTheEdgesThatMeet) {
    // An end block shorter than the wall is deep: its bed face is 0.6 x 0.55 where the
    // block below has 1.0 x 0.6. The side across the wall (0.6) meets the same side.
    const BlockFeatures below = box_features(Eigen::Vector3d(1.0, 0.6, 0.5), 0.0);
    const BlockFeatures above = box_features(Eigen::Vector3d(0.55, 0.6, 0.5), 0.0);
    const FacePairScore s = score_face_pair(below, kTop, above, kBottom, {});
    EXPECT_NEAR(check(s, Check::kSize), 0.5, 1e-9);  // Across agrees, along does not.
}

TEST(FaceMatching, ClampChannelsInABedFaceAreNotDowels) {
    BlockFeatures a = box_features(kBlock, 0.0), b = box_features(kBlock, 0.0);
    add_clamp_half(a, kPosX, 0.12, 0.04, 0.07, 0.0);
    add_clamp_half(b, kPosX, 0.12, 0.04, 0.07, 0.0);
    // The two top faces carry clamps at the same place; top against bottom or top against
    // top, no dowel pairs them.
    EXPECT_DOUBLE_EQ(check(score_face_pair(a, kTop, b, kTop, {}), Check::kHoles), 0.0);
    FaceHole dowel{.kind = HoleKind::kDowel, .length_m = 0.03, .width_m = 0.03, .depth_m = 0.05};
    dowel.centre_m = Eigen::Vector3d(0.2, -0.1, 0.275);
    a.faces[kTop].holes.push_back(dowel);
    dowel.centre_m = Eigen::Vector3d(-0.1, -0.1, -0.275);
    b.faces[kBottom].holes.push_back(dowel);
    EXPECT_GT(check(score_face_pair(a, kTop, b, kBottom, {}), Check::kHoles), 0.5);
}

}  // namespace
}  // namespace anascan::reassembly
