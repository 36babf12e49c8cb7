// The field app's panels in a headless ImGui context: simulated clicks and keys give the
// operator's actions as values; the failure banner appears exactly when it must.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "anascan/gui/panels.hpp"
#include "anascan/gui/theme.hpp"
#include "anascan/gui/view_overlay.hpp"
#include "anascan/processing/surface/fragment_model.hpp"
#include "headless_imgui.hpp"

namespace anascan::gui {
namespace {

using std::chrono::system_clock;

ScanRow row(std::int64_t seq, ScanRowState state, double rms_mm = 0.4) {
    return {.seq = seq,
            .device_id = "sim:tof/0",
            .captured_at = system_clock::time_point(std::chrono::seconds(1'700'000'000 + seq)),
            .state = state,
            .rms_mm = rms_mm,
            .overlap_percent = 60.0,
            .group = 0};
}

FieldViewState four_registered_scans() {
    FieldViewState state;
    for (std::int64_t seq = 1; seq <= 4; ++seq)
        state.scans.push_back(row(seq, ScanRowState::kRegistered));
    state.device.devices = {
        {.id = "sim:tof/0", .kind = "time-of-flight", .connected = true, .status = "ready"}};
    state.device.active_device = 0;
    state.status = {
        .coverage_percent = 72.5, .queued_registrations = 1, .disk_free_bytes = 40'000'000'000ull};
    return state;
}

constexpr PanelLayout kLayout{};

/// Clicks down a vertical line through a panel, returning every action in order of y.
UiActions sweep_clicks(HeadlessImGui& ui, const FieldViewState& state, float x, float y0,
                       float y1) {
    UiActions all;
    for (float y = y0; y < y1; y += 3.0f) {
        UiActions actions;
        ui.click([&] { draw_field_panels(state, kLayout, actions); }, ImVec2(x, y));
        all.insert(all.end(), actions.begin(), actions.end());
    }
    return all;
}

std::vector<std::int64_t> distinct_seqs(const UiActions& actions, UiActionKind kind) {
    std::vector<std::int64_t> seqs;
    for (const UiAction& a : actions) {
        if (a.kind == kind && (seqs.empty() || seqs.back() != a.seq)) seqs.push_back(a.seq);
    }
    return seqs;
}

TEST(ScanListPanel, ClickingEachRowSelectsItsScanInCaptureOrder) {
    HeadlessImGui ui;
    const FieldViewState state = four_registered_scans();
    UiActions warmup;
    ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
    const UiActions actions = sweep_clicks(ui, state, 30.0f, 0.0f, 400.0f);
    EXPECT_EQ(distinct_seqs(actions, UiActionKind::kSelectScan),
              (std::vector<std::int64_t>{1, 2, 3, 4}));
    EXPECT_TRUE(HeadlessImGui::window_drawn("Scans"));
    EXPECT_TRUE(HeadlessImGui::window_drawn("Status"));
    EXPECT_TRUE(HeadlessImGui::window_drawn("Device"));
}

TEST(ScanListPanel, SelectedScanOffersExcludeAndReRegister) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.selected_seq = 3;
    UiActions warmup;
    ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
    // The buttons sit on the first line under the title bar, left to right.
    UiActions actions;
    for (float x = 5.0f; x < kLayout.scan_list_width_px; x += 4.0f) {
        for (float y = 20.0f; y < 60.0f; y += 6.0f) {
            ui.click([&] { draw_field_panels(state, kLayout, actions); }, ImVec2(x, y));
        }
    }
    EXPECT_EQ(distinct_seqs(actions, UiActionKind::kExclude), (std::vector<std::int64_t>{3}));
    EXPECT_EQ(distinct_seqs(actions, UiActionKind::kReRegister), (std::vector<std::int64_t>{3}));
}

TEST(FailureBanner, ShownWhenTheNewestOutcomeFailedAndClearedByALaterSuccess) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.scans.push_back(row(5, ScanRowState::kFailed));
    state.scans.back().message = "overlap 8 % below 30 %";
    state.scans.push_back(row(6, ScanRowState::kQueued));  // still waiting: banner stays
    UiActions actions;
    bool drawn = false;
    ui.frame([&] { drawn = draw_failure_banner(state, kLayout, actions); });
    EXPECT_TRUE(drawn);
    EXPECT_TRUE(HeadlessImGui::window_drawn("Registration failed"));
    const auto banner = failure_banner(state);
    ASSERT_TRUE(banner.has_value());
    EXPECT_EQ(banner->seq, 5);
    EXPECT_NE(banner->message.find("overlap 8 %"), std::string::npos);
    EXPECT_FALSE(banner->what_to_try.empty());

    state.scans.back().state = ScanRowState::kRegistered;  // scan 6 registered: recovered
    ui.frame([&] { drawn = draw_failure_banner(state, kLayout, actions); });
    EXPECT_FALSE(drawn);
    EXPECT_FALSE(HeadlessImGui::window_drawn("Registration failed"));
    EXPECT_FALSE(failure_banner(state).has_value());
}

TEST(FailureBanner, ItsButtonExcludesTheFailedScan) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.scans.push_back(row(5, ScanRowState::kFailed));
    UiActions warmup;
    ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
    const float x = kLayout.view_x_px() + 60.0f;
    const UiActions actions = sweep_clicks(ui, state, x, 0.0f, kLayout.banner_height_px);
    EXPECT_EQ(distinct_seqs(actions, UiActionKind::kExclude), (std::vector<std::int64_t>{5}));
}

TEST(SplitBanner, WarnsWhenRegisteredScansSitInMoreThanOneGroup) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    EXPECT_FALSE(session_banner(state).has_value()) << "one group: no banner";
    // Scan 1 alone in group 0, scans 2-4 in group 1 (the view shows group 1).
    for (ScanRow& r : state.scans) r.group = r.seq == 1 ? 0 : 1;
    const auto banner = session_banner(state);
    ASSERT_TRUE(banner.has_value());
    EXPECT_EQ(banner->kind, BannerKind::kSplit);
    EXPECT_EQ(banner->seq, 1) << "the one scan outside the shown group";
    EXPECT_NE(banner->message.find("split in 2 parts"), std::string::npos) << banner->message;
    EXPECT_NE(banner->details.find("scan 1 not joined"), std::string::npos) << banner->details;
    EXPECT_NE(banner->details.find("scans 2-4, group 1"), std::string::npos) << banner->details;
    EXPECT_NE(banner->what_to_try.find("overlaps both parts"), std::string::npos);
    UiActions actions;
    bool drawn = false;
    ui.frame([&] { drawn = draw_failure_banner(state, kLayout, actions); });
    EXPECT_TRUE(drawn);
    EXPECT_TRUE(HeadlessImGui::window_drawn("Model split"));
    EXPECT_FALSE(HeadlessImGui::window_drawn("Registration failed"));

    // A newer failure takes the banner; two scans apart: no exclude button.
    state.scans[1].group = 0;
    EXPECT_EQ(split_banner(state)->seq, -1);
    state.scans.push_back(row(5, ScanRowState::kFailed));
    EXPECT_EQ(session_banner(state)->kind, BannerKind::kFailed);
    // Excluding the scans of the smaller part joins nothing but ends the warning.
    state.scans.pop_back();
    state.scans[0].state = state.scans[1].state = ScanRowState::kExcluded;
    EXPECT_FALSE(session_banner(state).has_value());
}

TEST(SplitBanner, ItsButtonExcludesTheStrayScan) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.scans[3].group = 2;  // scan 4 alone in group 2
    UiActions warmup;
    ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
    ui.frame([&] { draw_field_panels(state, kLayout, warmup); });  // height fits the text
    const ImGuiWindow* banner = ImGui::FindWindowByName("Model split");
    ASSERT_NE(banner, nullptr);
    EXPECT_GE(banner->Size.y, kLayout.banner_height_px);
    const float x = kLayout.view_x_px() + 60.0f;
    const UiActions actions = sweep_clicks(ui, state, x, 0.0f, banner->Size.y);
    EXPECT_EQ(distinct_seqs(actions, UiActionKind::kExclude), (std::vector<std::int64_t>{4}));
}

TEST(CaptureBanner, ACaptureProblemTakesTheBannerUntilCleared) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.scans.push_back(row(5, ScanRowState::kFailed));
    state.capture_problem = CaptureProblem{.headline = "DISK FULL: the scan was NOT saved",
                                           .details = "cannot save scan 6 in session /s",
                                           .what_to_try = "Free space"};
    const auto banner = session_banner(state);
    ASSERT_TRUE(banner.has_value());
    EXPECT_EQ(banner->kind, BannerKind::kCaptureFailed);
    EXPECT_EQ(banner->seq, -1) << "no exclude button: nothing was saved";
    UiActions actions;
    ui.frame([&] { draw_failure_banner(state, kLayout, actions); });
    EXPECT_TRUE(HeadlessImGui::window_drawn("Capture failed"));
    state.capture_problem.reset();
    EXPECT_EQ(session_banner(state)->kind, BannerKind::kFailed);
}

TEST(SplitBanner, ScanListsAreShort) {
    EXPECT_EQ(format_scan_list({4}), "scan 4");
    EXPECT_EQ(format_scan_list({2, 3, 4, 5}), "scans 2-5");
    EXPECT_EQ(format_scan_list({1, 3, 4, 5, 9}), "scans 1, 3-5, 9");
}

TEST(Shortcuts, SpaceCapturesXExcludesTheNewestTMarksTurnedOver) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.scans.back().state = ScanRowState::kExcluded;  // already excluded: newest is 3
    auto press = [&](int key) {
        UiActions actions;
        ui.frame([&] { handle_shortcuts(state, actions); });  // key up
        ui.frame([&] { handle_shortcuts(state, actions); }, ImVec2(-1, -1), false, key);
        return actions;
    };
    EXPECT_EQ(press(kKeyCapture), (UiActions{{.kind = UiActionKind::kCapture}}));
    EXPECT_EQ(press(kKeyExcludeLast), (UiActions{{.kind = UiActionKind::kExclude, .seq = 3}}));
    EXPECT_EQ(press(kKeyTurnedOver), (UiActions{{.kind = UiActionKind::kTurnedOver}}));
    state.device.capturing = true;  // no second capture while one runs
    EXPECT_TRUE(press(kKeyCapture).empty());
}

TEST(DevicePanel, CaptureButtonOnlyWithAnActiveIdleDevice) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    const float x = kLayout.width_px - kLayout.device_width_px + 40.0f;
    auto captures = [&] {
        UiActions warmup;
        ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
        const UiActions actions = sweep_clicks(ui, state, x, 0.0f, 400.0f);
        return std::count_if(actions.begin(), actions.end(),
                             [](const UiAction& a) { return a.kind == UiActionKind::kCapture; });
    };
    EXPECT_GT(captures(), 0);
    state.device.active_device = -1;
    EXPECT_EQ(captures(), 0);
}

TEST(Panels, SameStateDrawsTheSameFrame) {
    // No hidden state: two frames from one state and no input give identical geometry.
    HeadlessImGui ui;
    const FieldViewState state = four_registered_scans();
    auto vertices = [&] {
        UiActions actions;
        ui.frame([&] { draw_field_panels(state, kLayout, actions); });
        return ImGui::GetDrawData()->TotalVtxCount;
    };
    vertices();  // first frame sizes the windows
    const int a = vertices();
    EXPECT_GT(a, 0);
    EXPECT_EQ(vertices(), a);
}

TEST(Theme, HighContrastIsBlackAndWhiteAndSwitchingBackDoesNotAccumulateScaling) {
    HeadlessImGui ui;
    apply_theme({.high_contrast = true, .font_scale = 2.0f}, /*font_already_scaled=*/false);
    const ImGuiStyle& style = ImGui::GetStyle();
    EXPECT_EQ(style.Colors[ImGuiCol_WindowBg].x, 0.0f);
    EXPECT_EQ(style.Colors[ImGuiCol_Text].x, 1.0f);
    EXPECT_FLOAT_EQ(ImGui::GetIO().FontGlobalScale, 2.0f);
    const float padding = style.WindowPadding.x;
    apply_theme({.high_contrast = false, .font_scale = 2.0f}, false);
    apply_theme({.high_contrast = true, .font_scale = 2.0f}, false);
    EXPECT_FLOAT_EQ(ImGui::GetStyle().WindowPadding.x, padding);
    EXPECT_FLOAT_EQ(padding, 2.0f * ImGuiStyle().WindowPadding.x);
    apply_theme({.font_scale = 2.0f}, /*font_already_scaled=*/true);
    EXPECT_FLOAT_EQ(ImGui::GetIO().FontGlobalScale, 1.0f);
}

TEST(ViewActions, SelectionColourModeAndContrastChangeOnlyTheViewState) {
    FieldViewState state = four_registered_scans();
    EXPECT_TRUE(apply_view_action(state, {.kind = UiActionKind::kSelectScan, .seq = 2}));
    EXPECT_EQ(state.selected_seq, 2);
    EXPECT_TRUE(apply_view_action(
        state, {.kind = UiActionKind::kSetColorMode, .color_mode = ColorMode::kByQuality}));
    EXPECT_EQ(state.color_mode, ColorMode::kByQuality);
    EXPECT_TRUE(apply_view_action(state, {.kind = UiActionKind::kToggleContrast}));
    EXPECT_TRUE(state.high_contrast);
    EXPECT_FALSE(apply_view_action(state, {.kind = UiActionKind::kCapture}));
    EXPECT_FALSE(apply_view_action(state, {.kind = UiActionKind::kExclude, .seq = 1}));
}

}  // namespace
}  // namespace anascan::gui

namespace anascan::gui {
namespace {

/// The scan list's table, from the last frame.
ImGuiTable* scan_table() {
    ImGuiWindow* window = ImGui::FindWindowByName("Scans");
    if (window == nullptr) return nullptr;
    return ImGui::TableFindByID(window->GetID("scan_table"));
}

TEST(ScanListPanel, TheNewestScanStaysInTheListAsScansArrive) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    state.scans.clear();
    UiActions ignored;
    for (std::int64_t seq = 1; seq <= 60; ++seq) {  // one scan a frame, then two frames
        state.scans.push_back(row(seq, ScanRowState::kRegistered));
        ui.frame([&] { draw_field_panels(state, kLayout, ignored); });
    }
    ui.frame([&] { draw_field_panels(state, kLayout, ignored); });
    const UiActions actions =
        sweep_clicks(ui, state, 30.0f, 0.0f, kLayout.height_px - kLayout.status_height_px);
    const auto seqs = distinct_seqs(actions, UiActionKind::kSelectScan);
    ASSERT_FALSE(seqs.empty());
    EXPECT_EQ(seqs.back(), 60) << "the newest row can be clicked: it is in sight";
}

TEST(ScanListPanel, DeviceNamesAreNotCut) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    const std::string name = "sim:structured-light/octagon-block";
    for (ScanRow& r : state.scans) r.device_id = name;
    UiActions ignored;
    for (int pass = 0; pass < 2; ++pass) {
        ui.frame([&] { draw_field_panels(state, kLayout, ignored); });
        ui.frame([&] { draw_field_panels(state, kLayout, ignored); });
        ImGuiTable* table = scan_table();
        ASSERT_NE(table, nullptr);
        for (int c = 0; c < table->ColumnsCount; ++c) {
            if (std::string_view(ImGui::TableGetColumnName(table, c)) != "Device") continue;
            EXPECT_GE(table->Columns[c].WidthGiven, ImGui::CalcTextSize(name.c_str()).x)
                << "pass " << pass << ": the device column cuts " << name;
        }
        state.scans[1].device_id = "sim:tof/small-block";  // two devices: a column
    }
}

}  // namespace
}  // namespace anascan::gui

namespace anascan::gui {
namespace {

TEST(DisagreeBanner, ScansThatContradictTheirGroupAreNamedNotShownOk) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    EXPECT_FALSE(disagree_banner(state).has_value());
    state.scans[2].state = ScanRowState::kFlagged;
    state.scans[2].group = -1;
    state.scans[2].message = "scan 3 FLAGGED and taken out of group 0: free space";
    const auto banner = session_banner(state);
    ASSERT_TRUE(banner.has_value());
    EXPECT_EQ(banner->kind, BannerKind::kDisagree);
    EXPECT_EQ(banner->seq, 3);
    EXPECT_NE(banner->message.find("scan 3 contradicts"), std::string::npos) << banner->message;
    EXPECT_NE(banner->details.find("free space"), std::string::npos) << banner->details;
    EXPECT_STREQ(to_string(ScanRowState::kFlagged), "CONTRADICTS");
    UiActions actions;
    ui.frame([&] { draw_failure_banner(state, kLayout, actions); });
    EXPECT_TRUE(HeadlessImGui::window_drawn("Scans disagree"));
    // A newer failure still comes first; excluding the flagged scan ends the warning.
    state.scans.push_back(row(5, ScanRowState::kFailed));
    EXPECT_EQ(session_banner(state)->kind, BannerKind::kFailed);
    state.scans.pop_back();
    state.scans[2].state = ScanRowState::kExcluded;
    EXPECT_FALSE(session_banner(state).has_value());
}

TEST(MeshView, MakeTheMeshIsOfferedAndTheViewShowsAMeshOnlyOnceOneIsReady) {
    HeadlessImGui ui;
    FieldViewState state = four_registered_scans();
    const float x = kLayout.width_px - kLayout.device_width_px + 40.0f;
    auto clicked = [&](UiActionKind kind) {
        UiActions warmup;
        ui.frame([&] { draw_field_panels(state, kLayout, warmup); });
        const UiActions actions = sweep_clicks(ui, state, x, 0.0f, kLayout.height_px);
        return std::count_if(actions.begin(), actions.end(),
                             [&](const UiAction& a) { return a.kind == kind; });
    };
    EXPECT_GT(clicked(UiActionKind::kMakeMesh), 0);
    // No mesh yet: the view stays on the points whatever is asked.
    EXPECT_TRUE(apply_view_action(
        state, {.kind = UiActionKind::kSetViewMode, .view_mode = ViewMode::kMesh}));
    EXPECT_EQ(state.view_mode, ViewMode::kPoints);
    // While a mesh is being made, the button is disabled (no second one).
    state.mesh.status = MeshViewState::Status::kMaking;
    EXPECT_EQ(clicked(UiActionKind::kMakeMesh), 0);
    state.mesh = {.status = MeshViewState::Status::kReady, .scans = 4, .triangles = 812'000};
    // The points / mesh choice appears, on one line right of "Show".
    UiActions choice;
    for (float cx = x; cx < kLayout.width_px; cx += 25.0f) {
        const UiActions a = sweep_clicks(ui, state, cx, 0.0f, kLayout.height_px);
        choice.insert(choice.end(), a.begin(), a.end());
    }
    EXPECT_GT(std::count_if(choice.begin(), choice.end(),
                            [](const UiAction& a) {
                                return a.kind == UiActionKind::kSetViewMode &&
                                       a.view_mode == ViewMode::kMesh;
                            }),
              0);
    EXPECT_TRUE(apply_view_action(
        state, {.kind = UiActionKind::kSetViewMode, .view_mode = ViewMode::kMesh}));
    EXPECT_EQ(state.view_mode, ViewMode::kMesh);
}

TEST(MeshView, TheSummarySaysWhatTheMeshIsAndWhenItIsOutdated) {
    MeshViewState mesh;
    EXPECT_EQ(mesh_summary(mesh), "");
    mesh = {.status = MeshViewState::Status::kMaking, .message = "normals on 181863 merged points"};
    EXPECT_EQ(mesh_summary(mesh), "Making the mesh: normals on 181863 merged points");
    mesh = {.status = MeshViewState::Status::kFailed, .message = "cannot mesh: no points"};
    EXPECT_EQ(mesh_summary(mesh), "Mesh failed: cannot mesh: no points");
    mesh = {.status = MeshViewState::Status::kReady,
            .resolution_mm = 1.0,
            .scans = 12,
            .triangles = 1'234'567,
            .area_m2 = 0.412,
            .interpolated_share = 0.123,
            .closed = true,
            .seconds = 14.2,
            .outdated = "3 newer scans"};
    EXPECT_EQ(mesh_summary(mesh),
              "Mesh: 1.2 M triangles, 0.412 m\u00b2, 12.3 % interpolated, closed; 12 scans, "
              "1.0 mm, 14.2 s (outdated: 3 newer scans)");
}

TEST(MeshView, TheLegendNamesTheTwoSurfaceClassesInTheMeshFilesColours) {
    FieldViewState state = four_registered_scans();
    state.view_mode = ViewMode::kMesh;
    const std::vector<LegendEntry> legend = color_legend(state);
    ASSERT_EQ(legend.size(), 2u);
    EXPECT_EQ(legend[0].color, surface_class_color(SurfaceClass::kMeasured));
    EXPECT_EQ(legend[1].color, surface_class_color(SurfaceClass::kInterpolated));
    EXPECT_NE(legend[1].label.find("interpolated"), std::string::npos);
}

}  // namespace
}  // namespace anascan::gui
