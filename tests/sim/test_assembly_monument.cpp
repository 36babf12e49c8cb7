// The block assembly on simulated monument neighbours whose joint faces carry little
// geometry (anathyrosis only), from the Horn placement: non-penetration alone leaves no
// penetration; with co-planarity and co-linearity the truth is recovered (5 mm grid;
// scripts/assembly_figures.sh runs the longer checks).
#include <gtest/gtest.h>

#include "monument_assembly.hpp"

namespace anascan::sim {
namespace {

using namespace testing;

TEST(MonumentAssembly, NeighboursFromTheHornPlacement) {
    auto m = monument_assembly("octagon-wall", 0, {"c0b0", "c0b1"}, 0.005);
    ASSERT_TRUE(m) << m.error().message;
    for (const auto& l : m->problem.contacts) {
        ASSERT_GE(l.a.face, 0);
        ASSERT_GE(l.b.face, 0);
    }
    auto placed = ra::initial_placement(m->problem);
    ASSERT_TRUE(placed) << placed.error().message;
    const std::vector<Pose>& start = *placed;
    auto penetration_only =
        ra::assemble_blocks(m->problem, start, {.use_coplanar = false, .use_colinear = false});
    ASSERT_TRUE(penetration_only) << penetration_only.error().message;
    EXPECT_LE(ra::check_assembly(m->problem, penetration_only->T_world_block).penetration_max_m,
              1e-4);
    auto full = ra::assemble_blocks(m->problem, start, {});
    ASSERT_TRUE(full) << full.error().message;
    EXPECT_EQ(full->status, ra::AssemblyStatus::kOk)
        << full->message << ": " << (full->offending.empty() ? "" : full->offending[0]);
    const BlockError e = block_error(*m, full->T_world_block, 1);
    EXPECT_LT(e.rotation_deg, 0.1);
    EXPECT_LT(e.translation_m, 0.0005);
    EXPECT_LE(ra::check_assembly(m->problem, full->T_world_block).penetration_max_m, 1e-4);
}

}  // namespace
}  // namespace anascan::sim
