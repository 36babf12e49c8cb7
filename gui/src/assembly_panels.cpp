// The assembly view's panels: proposals (left), assembly (right), status bar.
#include <fmt/format.h>

#include <algorithm>

#include "anascan/acquisition/blocks/block_proposals.hpp"
#include "anascan/gui/assembly_view.hpp"
#include "panel_util.hpp"

namespace anascan::gui {
namespace {

constexpr std::size_t kShownCandidates = 3;

ImVec4 to_imgui(Rgb8 c) { return {c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, 1.0f}; }

/// One candidate: a checkbox that chooses the pair, the face, the score, the checks.
void draw_candidate(const AssemblyViewState& state, const std::string& face,
                    const AssemblyCandidateRow& c, UiActions& actions) {
    const std::string pair = acquisition::pair_name(face, c.face);
    bool chosen = state.chosen(pair);
    const bool busy =
        state.phase == AssemblyPhase::kLoading || state.phase == AssemblyPhase::kAligning;
    if (busy) ImGui::BeginDisabled();
    if (ImGui::Checkbox(fmt::format("{}##{}", c.face, pair).c_str(), &chosen))
        actions.push_back({.kind = UiActionKind::kTogglePair, .text = pair});
    if (busy) ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::TextUnformatted(fmt::format("{:.2f}", c.score).c_str());
    ImGui::SameLine();
    ImGui::TextColored(c.passed == c.checks ? detail::kColorGood : detail::kColorMuted, "%zu/%zu",
                       c.passed, c.checks);
    if (!c.passed_names.empty() && ImGui::IsItemHovered())
        ImGui::SetTooltip("checks passed: %s", c.passed_names.c_str());
    if (c.accepted) {
        ImGui::SameLine();
        ImGui::TextColored(detail::kColorGood, "accepted");
    }
}

void draw_proposals(const AssemblyViewState& state, const PanelLayout& layout, UiActions& actions) {
    detail::place_next_window(0.0f, 0.0f, layout.scan_list_width_px, layout.view_height_px());
    ImGui::Begin("Proposals", nullptr, detail::kClearedPanelFlags);
    if (state.proposals.empty())
        ImGui::TextWrapped("No proposals (run anascan blocks match, or give --proposals)");
    ImGui::TextColored(detail::kColorMuted, "Face: best candidates, score, checks passed");
    for (const AssemblyFaceRow& row : state.proposals) {
        if (!ImGui::TreeNodeEx(row.face.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
        // The best few (as `blocks match` prints them), and any chosen further down.
        for (std::size_t k = 0; k < row.candidates.size(); ++k) {
            const AssemblyCandidateRow& c = row.candidates[k];
            if (k < kShownCandidates || state.chosen(acquisition::pair_name(row.face, c.face)))
                draw_candidate(state, row.face, c, actions);
        }
        ImGui::TreePop();
    }
    ImGui::End();
}

void draw_blocks(const AssemblyViewState& state) {
    ImGui::Text("%zu blocks", state.blocks.size());
    for (const AssemblyBlockRow& b : state.blocks) {
        ImGui::ColorButton(fmt::format("##colour{}", b.id).c_str(), to_imgui(b.colour),
                           ImGuiColorEditFlags_NoTooltip);
        ImGui::SameLine();
        ImGui::TextUnformatted(b.fixed ? fmt::format("{} (fixed)", b.id).c_str() : b.id.c_str());
    }
}

/// Under each chosen pair, its neighbour pairs to make co-planar.
void draw_chosen_pairs(const AssemblyViewState& state, UiActions& actions) {
    ImGui::Text("Chosen pairs: %zu", state.chosen_pairs.size());
    const bool busy = state.phase == AssemblyPhase::kAligning;
    for (const std::string& p : state.chosen_pairs) {
        ImGui::BulletText("%s", p.c_str());
        ImGui::Indent();
        if (busy) ImGui::BeginDisabled();
        for (const std::string& n : state.neighbour_pairs(p)) {
            bool on = state.coplanar(n);
            if (ImGui::Checkbox(fmt::format("co-planar {}##{}", n, p).c_str(), &on))
                actions.push_back({.kind = UiActionKind::kToggleCoplanar, .text = n});
        }
        if (busy) ImGui::EndDisabled();
        ImGui::Unindent();
    }
}

void draw_report(const AssemblyReportView& r) {
    ImGui::TextColored(r.ok() ? detail::kColorGood : detail::kColorBad, "Alignment: %s",
                       r.status.c_str());
    ImGui::Text("%d iterations, %.1f s", r.iterations, r.seconds);
    if (!r.message.empty()) ImGui::TextWrapped("%s", r.message.c_str());
    for (const std::string& o : r.offending)
        ImGui::TextColored(detail::kColorBad, "offending: %s", o.c_str());
    ImGui::PushStyleColor(ImGuiCol_Text,
                          r.penetration_max_mm > 0.1 ? detail::kColorBad : detail::kColorGood);
    ImGui::TextWrapped("Penetration max %.2f mm, mean %.2f mm (%zu points)", r.penetration_max_mm,
                       r.penetration_mean_mm, r.penetrating_points);
    ImGui::PopStyleColor();
    for (const AssemblyPairFigures& p : r.pairs)
        ImGui::TextWrapped("%s: gap median %.2f mm, p95 %.2f mm, min %.2f mm", p.pair.c_str(),
                           p.gap_median_mm, p.gap_p95_mm, p.gap_min_mm);
    for (const AssemblyCoplanarFigures& c : r.coplanar)
        ImGui::TextWrapped("co-planar %s: %.3f deg, %.2f mm", c.pair.c_str(), c.angle_deg,
                           c.offset_mm);
    ImGui::PushStyleColor(ImGuiCol_Text, detail::kColorMuted);
    ImGui::TextWrapped(
        "Gap colours: green within 1 mm, yellow 3 mm, blue from 5 mm; red: "
        "penetration");
    ImGui::PopStyleColor();
}

void draw_buttons(const AssemblyViewState& state, UiActions& actions) {
    const bool can_align =
        (state.phase == AssemblyPhase::kReady || state.phase == AssemblyPhase::kAligned) &&
        !state.chosen_pairs.empty();
    if (!can_align) ImGui::BeginDisabled();
    const std::size_t n = state.chosen_pairs.size();
    if (ImGui::Button(fmt::format("Align by {} pair{}", n, n == 1 ? "" : "s").c_str()))
        actions.push_back({.kind = UiActionKind::kAlignBlocks});
    if (!can_align) ImGui::EndDisabled();
    const bool can_accept = state.phase == AssemblyPhase::kAligned && state.report &&
                            state.report->ok() && state.saved_to.empty();
    if (!can_accept) ImGui::BeginDisabled();
    if (ImGui::Button("Accept and save"))
        actions.push_back({.kind = UiActionKind::kAcceptAssembly});
    if (!can_accept) ImGui::EndDisabled();
}

void draw_assembly_panel(const AssemblyViewState& state, const PanelLayout& layout,
                         UiActions& actions) {
    detail::place_next_window(layout.width_px - layout.device_width_px, 0.0f,
                              layout.device_width_px, layout.view_height_px());
    ImGui::Begin("Assembly", nullptr, detail::kClearedPanelFlags);
    ImGui::TextWrapped("%s", state.folder.c_str());
    draw_blocks(state);
    ImGui::Separator();
    if (state.picked_face.empty())
        ImGui::TextColored(detail::kColorMuted, "Click a face in the view to pair it");
    else
        ImGui::TextColored(detail::kColorWarn, "Picked %s: click a face of another block",
                           state.picked_face.c_str());
    draw_chosen_pairs(state, actions);
    draw_buttons(state, actions);
    if (!state.progress.empty())
        ImGui::TextColored(detail::kColorWarn, "%s", state.progress.c_str());
    ImGui::Separator();
    if (state.report) draw_report(*state.report);
    if (!state.saved_to.empty()) ImGui::TextWrapped("Saved to %s", state.saved_to.c_str());
    ImGui::End();
}

void draw_assembly_status(const AssemblyViewState& state, const PanelLayout& layout) {
    detail::place_next_window(0.0f, layout.height_px - layout.status_height_px, layout.width_px,
                              layout.status_height_px);
    ImGui::Begin("Status", nullptr, detail::kClearedPanelFlags | ImGuiWindowFlags_NoTitleBar);
    ImGui::TextUnformatted(fmt::format("Assembly: {}", to_string(state.phase)).c_str());
    ImGui::SameLine(0.0f, 30.0f);
    if (state.last_error.empty())
        ImGui::TextColored(detail::kColorMuted, "No errors");
    else
        ImGui::TextColored(detail::kColorBad, "Error: %s", state.last_error.c_str());
    ImGui::End();
}

}  // namespace

const char* to_string(AssemblyPhase phase) {
    switch (phase) {
        case AssemblyPhase::kLoading:
            return "loading";
        case AssemblyPhase::kReady:
            return "ready";
        case AssemblyPhase::kAligning:
            return "aligning";
        case AssemblyPhase::kAligned:
            return "aligned";
        case AssemblyPhase::kFailed:
            return "failed";
    }
    return "?";
}

bool AssemblyViewState::chosen(const std::string& pair) const {
    return std::find(chosen_pairs.begin(), chosen_pairs.end(), pair) != chosen_pairs.end();
}

void draw_assembly_panels(const AssemblyViewState& state, const PanelLayout& layout,
                          UiActions& actions) {
    draw_proposals(state, layout, actions);
    draw_assembly_panel(state, layout, actions);
    draw_assembly_status(state, layout);
}

bool AssemblyViewState::coplanar(const std::string& pair) const {
    return std::find(chosen_coplanar.begin(), chosen_coplanar.end(), pair) != chosen_coplanar.end();
}

std::vector<std::string> AssemblyViewState::neighbour_pairs(const std::string& pair) const {
    for (const AssemblyFaceRow& row : proposals)
        for (const AssemblyCandidateRow& c : row.candidates)
            if (acquisition::pair_name(row.face, c.face) == pair) return c.neighbour_pairs;
    return {};
}

namespace {

/// Adds `item` when absent, else removes it; true when it was added.
bool toggle(std::vector<std::string>& list, const std::string& item) {
    const auto it = std::find(list.begin(), list.end(), item);
    if (it == list.end()) {
        list.push_back(item);
        return true;
    }
    list.erase(it);
    return false;
}

std::string block_of(const std::string& face) { return face.substr(0, face.rfind(':')); }

void toggle_pair(AssemblyViewState& state, const std::string& pair) {
    if (!toggle(state.chosen_pairs, pair))
        for (const std::string& n : state.neighbour_pairs(pair))
            std::erase(state.chosen_coplanar, n);
}

/// The first face clicked waits; a face of another block pairs with it.
void pick_face(AssemblyViewState& state, const std::string& face) {
    if (face.empty() || state.picked_face.empty() ||
        block_of(face) == block_of(state.picked_face)) {
        state.picked_face = face;
        return;
    }
    toggle_pair(state, acquisition::pair_name(state.picked_face, face));
    state.picked_face.clear();
}

}  // namespace

bool apply_assembly_view_action(AssemblyViewState& state, const UiAction& action) {
    const UiActionKind k = action.kind;
    if (k != UiActionKind::kTogglePair && k != UiActionKind::kToggleCoplanar &&
        k != UiActionKind::kPickFace)
        return false;
    if (state.phase == AssemblyPhase::kLoading || state.phase == AssemblyPhase::kAligning)
        return true;  // the links of a running alignment stay as they are
    if (k == UiActionKind::kToggleCoplanar)
        toggle(state.chosen_coplanar, action.text);
    else if (k == UiActionKind::kPickFace)
        pick_face(state, action.text);
    else
        toggle_pair(state, action.text);
    return true;
}

}  // namespace anascan::gui
