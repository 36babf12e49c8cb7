// The simulated monument: its layout and truth (joints touch, clamp halves and dowels meet
// across them), and block features measured on its fallen blocks against that truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "anascan/processing/reassembly/block_features.hpp"
#include "anascan/processing/reassembly/face_matching.hpp"
#include "anascan/sim/monument.hpp"

namespace anascan::sim {
namespace {

namespace ra = anascan::reassembly;

Eigen::Vector3d face_centre_monument(const MonumentBlock& b, BlockFace f) {
    const Eigen::Vector3d n = face_normal(f);
    return b.T_monument_block * (0.5 * n.cwiseProduct(b.config.size_m));
}

TEST(Monument, NamedSectionsAndJointsTouch) {
    for (const char* name : {"octagon-base-course", "octagon-wall", "octagon-wall-3"}) {
        for (std::uint64_t seed : {0ull, 5ull, 77ull}) {
            auto config = named_monument(name, seed);
            ASSERT_TRUE(config);
            auto m = make_monument(*config);
            ASSERT_TRUE(m) << m.error().message;
            EXPECT_EQ(m->blocks.size(), std::size_t(config->courses * config->blocks_per_course));
            int vertical = 0;
            for (const JointPair& j : m->joints) {
                const MonumentBlock &a = m->blocks[j.a.block], &b = m->blocks[j.b.block];
                const Eigen::Vector3d n = face_normal(j.a.face);
                EXPECT_NEAR(
                    n.dot(face_centre_monument(a, j.a.face) - face_centre_monument(b, j.b.face)),
                    0.0, 1e-9);
                EXPECT_NEAR(n.dot(face_normal(j.b.face)), -1.0, 1e-12);
                vertical += j.kind == JointKind::kVertical;
            }
            EXPECT_EQ(vertical, config->courses * (config->blocks_per_course - 1));
            for (const MonumentBlock& b : m->blocks) {
                EXPECT_GE(b.config.size_m.x(), config->min_block_length_m - 1e-9);
                EXPECT_LE(b.config.size_m.x(), config->max_block_length_m + 1e-9);
                // Fallen: resting on the ground.
                EXPECT_NEAR(b.T_ground_block.translation().z() -
                                0.5 * (b.T_ground_block.linear().cwiseAbs() * b.config.size_m).z(),
                            0.0, 1e-9);
            }
        }
    }
    EXPECT_FALSE(named_monument("parthenon"));
}

TEST(Monument, ClampHalvesMeetAcrossVerticalJoints) {
    auto m = make_monument(*named_monument("octagon-wall"));
    ASSERT_TRUE(m);
    for (const JointPair& j : m->joints) {
        if (j.kind != JointKind::kVertical) continue;
        const MonumentBlock &a = m->blocks[j.a.block], &b = m->blocks[j.b.block];
        ASSERT_FALSE(a.config.clamp_holes.empty());
        ASSERT_FALSE(b.config.clamp_holes.empty());
        const ClampHole& ha = a.config.clamp_holes.back();  // +x half (added last on a).
        const ClampHole& hb = b.config.clamp_holes.front();
        EXPECT_EQ(ha.edge_face, BlockFace::kPosX);
        EXPECT_EQ(hb.edge_face, BlockFace::kNegX);
        EXPECT_DOUBLE_EQ(ha.offset_m, -hb.offset_m);  // The same monument y.
    }
}

// Features of fallen blocks against the truth: every face found with its normal, size and
// roughness order, and the clamp halves and dowels.
TEST(MonumentFeatures, FallenBlocksAgainstTruth) {
    auto config = named_monument("octagon-wall");
    ASSERT_TRUE(config);
    auto m = make_monument(*config);
    ASSERT_TRUE(m);
    int holes_true = 0, holes_found = 0;
    for (int i : {0, 3, 9}) {
        const MonumentBlock& b = m->blocks[i];
        const ra::BlockFeatures f =
            ra::extract_block_features(transformed_mesh(block_mesh(b), b.T_ground_block), {});
        ASSERT_EQ(f.status, ra::BlockStatus::kOk) << b.id << ": " << f.message;
        EXPECT_GE(f.faces.size(), 6u) << b.id;  // Broken corners may add small faces.
        const Eigen::Matrix3d R = b.T_ground_block.linear();
        double rough_facade = 0, rough_back = 0, rough_joint = 0, rough_bed = 0;
        for (int face = 0; face < kBlockFaceCount; ++face) {
            const Eigen::Vector3d n = R * face_normal(BlockFace(face));
            const ra::PlanarFace* found = nullptr;
            for (const ra::PlanarFace& p : f.faces)
                if (p.normal.dot(n) > std::cos(2.0 * std::numbers::pi / 180)) found = &p;
            ASSERT_NE(found, nullptr) << b.id << " face " << face_name(BlockFace(face));
            EXPECT_LT(std::acos(std::min(1.0, found->normal.dot(n))) * 180 / std::numbers::pi, 0.3);
            const Eigen::Vector3d in_plane =
                (Eigen::Vector3d::Ones() - face_normal(BlockFace(face)).cwiseAbs())
                    .cwiseProduct(b.config.size_m);
            const double w = in_plane.maxCoeff(), h = (in_plane.sum() - w);
            EXPECT_NEAR(found->width_m, w, 0.005) << b.id << " " << face_name(BlockFace(face));
            EXPECT_NEAR(found->height_m, h, 0.005) << b.id << " " << face_name(BlockFace(face));
            if (face == int(BlockFace::kPosY)) rough_facade = found->roughness_per_m2;
            if (face == int(BlockFace::kNegY)) rough_back = found->roughness_per_m2;
            if (face == int(BlockFace::kPosX)) rough_joint = found->roughness_per_m2;
            if (face == int(BlockFace::kPosZ)) rough_bed = found->roughness_per_m2;
            holes_found += int(found->holes.size());
        }
        // Façade smoothest, back roughest; bed and joint faces are both in between.
        EXPECT_LT(rough_facade, std::min(rough_bed, rough_joint)) << b.id;
        EXPECT_LT(std::max(rough_bed, rough_joint), rough_back) << b.id;
        holes_true += int(b.config.clamp_holes.size() + b.config.dowel_holes.size());
    }
    // Recall over these blocks; a clamp half cut by a chip can be missed.
    EXPECT_GE(holes_found, holes_true - 1);
    EXPECT_LE(holes_found, holes_true);
}

}  // namespace
}  // namespace anascan::sim
