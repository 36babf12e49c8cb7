// The assembly view's panels in a headless ImGui context: ticking a candidate chooses its
// pair (one name for both orders), the best three candidates shown (and a chosen one), Align needs
// a chosen pair and no running work, Accept needs an ok alignment, and the report names the
// offending pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "anascan/gui/assembly_view.hpp"
#include "headless_imgui.hpp"

namespace anascan::gui {
namespace {

constexpr PanelLayout kLayout{};

AssemblyViewState two_blocks() {
    AssemblyViewState s{.folder = "/tmp/f", .phase = AssemblyPhase::kReady};
    s.blocks = {{.id = "c0b0", .colour = {230, 159, 0}, .fixed = true},
                {.id = "c0b1", .colour = {86, 180, 233}}};
    s.proposals = {{.face = "c0b1:4",
                    .candidates = {{.face = "c0b0:2",
                                    .score = 0.91,
                                    .passed = 6,
                                    .checks = 6,
                                    .neighbour_pairs = {"c0b0:0=c0b1:1", "c0b0:3=c0b1:5"}},
                                   {.face = "c0b0:5", .score = 0.40, .passed = 3, .checks = 6},
                                   {.face = "c0b0:1", .score = 0.30, .passed = 2, .checks = 6},
                                   {.face = "c0b0:3", .score = 0.20, .passed = 1, .checks = 6}}}};
    return s;
}

// Clicks over a rectangle of the window on a grid; every action, in order.
UiActions sweep(HeadlessImGui& ui, const AssemblyViewState& s, float x0, float x1, float y0,
                float y1) {
    UiActions all;
    UiActions warmup;
    ui.frame([&] { draw_assembly_panels(s, kLayout, warmup); });
    for (float y = y0; y < y1; y += 4.0f)
        for (float x = x0; x < x1; x += 12.0f) {
            UiActions actions;
            ui.click([&] { draw_assembly_panels(s, kLayout, actions); }, ImVec2(x, y));
            all.insert(all.end(), actions.begin(), actions.end());
        }
    return all;
}

std::size_t count(const UiActions& actions, UiActionKind kind) {
    return std::size_t(std::count_if(actions.begin(), actions.end(),
                                     [&](const UiAction& a) { return a.kind == kind; }));
}

TEST(AssemblyPanels, TickingACandidateChoosesItsPairAndTickingAgainDropsIt) {
    HeadlessImGui ui;
    AssemblyViewState s = two_blocks();
    const UiActions actions = sweep(ui, s, 5.0f, 60.0f, 0.0f, 200.0f);
    std::vector<std::string> pairs;
    for (const UiAction& a : actions)
        if (a.kind == UiActionKind::kTogglePair &&
            std::find(pairs.begin(), pairs.end(), a.text) == pairs.end())
            pairs.push_back(a.text);
    // The best three, named with the faces in name order whatever the row's face.
    EXPECT_EQ(pairs, (std::vector<std::string>{"c0b0:2=c0b1:4", "c0b0:5=c0b1:4", "c0b0:1=c0b1:4"}));
    EXPECT_TRUE(HeadlessImGui::window_drawn("Proposals"));
    EXPECT_TRUE(HeadlessImGui::window_drawn("Assembly"));

    const UiAction tick{.kind = UiActionKind::kTogglePair, .text = "c0b0:2=c0b1:4"};
    EXPECT_TRUE(apply_assembly_view_action(s, tick));
    EXPECT_TRUE(s.chosen("c0b0:2=c0b1:4"));
    EXPECT_TRUE(apply_assembly_view_action(s, tick));
    EXPECT_FALSE(s.chosen("c0b0:2=c0b1:4"));
    // A chosen candidate further down stays in the list (to be dropped again).
    s.chosen_pairs = {"c0b0:3=c0b1:4"};
    bool fourth_shown = false;
    for (const UiAction& a : sweep(ui, s, 5.0f, 60.0f, 0.0f, 200.0f))
        fourth_shown = fourth_shown || a.text == "c0b0:3=c0b1:4";
    EXPECT_TRUE(fourth_shown);
    s.chosen_pairs.clear();
    // While an alignment runs its pairs stay as they are.
    s.phase = AssemblyPhase::kAligning;
    EXPECT_TRUE(apply_assembly_view_action(s, tick));
    EXPECT_TRUE(s.chosen_pairs.empty());
    EXPECT_FALSE(apply_assembly_view_action(s, {.kind = UiActionKind::kAlignBlocks}));
}

TEST(AssemblyPanels, AlignNeedsAChosenPairAndAcceptAnOkAlignment) {
    HeadlessImGui ui;
    const float right = kLayout.width_px - kLayout.device_width_px;
    AssemblyViewState s = two_blocks();
    UiActions none = sweep(ui, s, right + 5.0f, kLayout.width_px, 0.0f, 400.0f);
    EXPECT_EQ(count(none, UiActionKind::kAlignBlocks), 0u);
    EXPECT_EQ(count(none, UiActionKind::kAcceptAssembly), 0u);

    s.chosen_pairs = {"c0b0:2=c0b1:4"};
    UiActions align = sweep(ui, s, right + 5.0f, kLayout.width_px, 0.0f, 400.0f);
    EXPECT_GT(count(align, UiActionKind::kAlignBlocks), 0u);
    EXPECT_EQ(count(align, UiActionKind::kAcceptAssembly), 0u);

    s.phase = AssemblyPhase::kAligning;  // busy: neither
    UiActions busy = sweep(ui, s, right + 5.0f, kLayout.width_px, 0.0f, 400.0f);
    EXPECT_EQ(count(busy, UiActionKind::kAlignBlocks), 0u);

    s.phase = AssemblyPhase::kAligned;
    s.report = AssemblyReportView{.status = "infeasible", .offending = {"c0b0:2=c0b1:4"}};
    UiActions refused = sweep(ui, s, right + 5.0f, kLayout.width_px, 0.0f, 500.0f);
    EXPECT_EQ(count(refused, UiActionKind::kAcceptAssembly), 0u);

    s.report = AssemblyReportView{.status = "ok", .iterations = 4};
    UiActions accept = sweep(ui, s, right + 5.0f, kLayout.width_px, 0.0f, 500.0f);
    EXPECT_GT(count(accept, UiActionKind::kAcceptAssembly), 0u);
}

TEST(AssemblyPanels, AChosenPairOffersItsNeighbourPairsAsCoplanarLinks) {
    HeadlessImGui ui;
    const float right = kLayout.width_px - kLayout.device_width_px;
    AssemblyViewState s = two_blocks();
    s.chosen_pairs = {"c0b0:2=c0b1:4"};
    std::vector<std::string> offered;
    for (const UiAction& a : sweep(ui, s, right + 5.0f, kLayout.width_px, 0.0f, 400.0f))
        if (a.kind == UiActionKind::kToggleCoplanar &&
            std::find(offered.begin(), offered.end(), a.text) == offered.end())
            offered.push_back(a.text);
    EXPECT_EQ(offered, (std::vector<std::string>{"c0b0:0=c0b1:1", "c0b0:3=c0b1:5"}));

    EXPECT_TRUE(apply_assembly_view_action(
        s, {.kind = UiActionKind::kToggleCoplanar, .text = "c0b0:0=c0b1:1"}));
    EXPECT_TRUE(s.coplanar("c0b0:0=c0b1:1"));
    // Dropping the pair drops its co-planar links.
    EXPECT_TRUE(apply_assembly_view_action(
        s, {.kind = UiActionKind::kTogglePair, .text = "c0b0:2=c0b1:4"}));
    EXPECT_TRUE(s.chosen_coplanar.empty());
}

TEST(AssemblyPanels, AFaceClickedThenAFaceOfAnotherBlockChoosesTheirPair) {
    AssemblyViewState s = two_blocks();
    auto pick = [&](const std::string& face) {
        EXPECT_TRUE(apply_assembly_view_action(s, {.kind = UiActionKind::kPickFace, .text = face}));
    };
    pick("c0b1:4");
    EXPECT_EQ(s.picked_face, "c0b1:4");
    pick("c0b1:2");  // the same block: the new face waits instead
    EXPECT_EQ(s.picked_face, "c0b1:2");
    pick("c0b0:5");
    EXPECT_EQ(s.chosen_pairs, (std::vector<std::string>{"c0b0:5=c0b1:2"}));
    EXPECT_TRUE(s.picked_face.empty());
    pick("c0b0:5");
    pick("c0b1:2");  // the same pair again: dropped
    EXPECT_TRUE(s.chosen_pairs.empty());
    pick("c0b0:1");
    pick("");  // a click beside the blocks
    EXPECT_TRUE(s.picked_face.empty());
}

}  // namespace
}  // namespace anascan::gui
