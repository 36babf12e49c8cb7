#pragma once
/// \file
/// The archaeologist's assembly view of anascan-field (`--assembly DIR`): the blocks of a
/// folder of block features in 3D, the neighbour proposals with their scores and checks,
/// the face pairs chosen for the alignment, the alignment's report (status, penetration,
/// gaps) and its acceptance into an assembly folder. The state is plain data; the panels
/// draw it and return the operator's requests as UiActions.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "anascan/gui/panels.hpp"
#include "anascan/gui/ui_action.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::gui {

enum class AssemblyPhase {
    kLoading,   ///< Models read and their features found (worker thread).
    kReady,     ///< Blocks shown where they lie; pairs can be chosen.
    kAligning,  ///< The alignment runs (worker thread); the view stays live.
    kAligned,   ///< A result is shown (whatever its status).
    kFailed,    ///< The folder could not be loaded.
};
const char* to_string(AssemblyPhase phase);

struct AssemblyBlockRow {
    std::string id;
    Rgb8 colour;
    bool fixed = false;
};

struct AssemblyCandidateRow {
    std::string face;  ///< "BLOCK:FACE".
    double score = 0.0;
    std::size_t passed = 0, checks = 0;
    std::string passed_names;  ///< "size,roughness,..." for the tooltip.
    bool accepted = false;     ///< By the expert (blocks accept).
    /// Neighbouring faces paired around the two ("A:F=B:G"): co-planar links to offer.
    std::vector<std::string> neighbour_pairs;
};

struct AssemblyFaceRow {
    std::string face;
    std::vector<AssemblyCandidateRow> candidates;  ///< Best first.
};

struct AssemblyPairFigures {
    std::string pair;
    double gap_median_mm = 0.0, gap_p95_mm = 0.0, gap_min_mm = 0.0;
};

struct AssemblyCoplanarFigures {
    std::string pair;
    double angle_deg = 0.0, offset_mm = 0.0;
};

struct AssemblyReportView {
    std::string status;  ///< "ok", "infeasible", "contradictory", "not converged".
    std::string message;
    std::vector<std::string> offending;
    int iterations = 0;
    double seconds = 0.0;
    double penetration_max_mm = 0.0, penetration_mean_mm = 0.0;
    std::size_t penetrating_points = 0;
    std::vector<AssemblyPairFigures> pairs;
    std::vector<AssemblyCoplanarFigures> coplanar;
    bool ok() const { return status == "ok"; }
};

struct AssemblyViewState {
    std::string folder;
    AssemblyPhase phase = AssemblyPhase::kLoading;
    std::string progress;  ///< "Loading block 3 of 12" while a worker runs.
    std::vector<AssemblyBlockRow> blocks;
    std::vector<AssemblyFaceRow> proposals;
    std::vector<std::string> chosen_pairs;  ///< "A:F=B:G", as acquisition::pair_name writes them.
    /// Faces made co-planar ("A:F=B:G"), among the neighbour pairs of the chosen pairs.
    std::vector<std::string> chosen_coplanar;
    /// A face clicked in the view ("A:F"), waiting for a face of another block to pair with.
    std::string picked_face;
    std::optional<AssemblyReportView> report;
    std::string saved_to;  ///< The assembly folder once accepted.
    std::string last_error;
    bool chosen(const std::string& pair) const;
    bool coplanar(const std::string& pair) const;
    /// The neighbour pairs the proposals give for a face pair (either order of its faces).
    std::vector<std::string> neighbour_pairs(const std::string& pair) const;
};

/// The proposals (left), the assembly panel (right) and the status bar.
void draw_assembly_panels(const AssemblyViewState& state, const PanelLayout& layout,
                          UiActions& actions);

/// Applies a view-only assembly action (choosing or dropping a pair, a co-planar link; a
/// dropped pair takes its co-planar links with it; a face clicked, then a face of another
/// block: their pair chosen or dropped); false for the others.
bool apply_assembly_view_action(AssemblyViewState& state, const UiAction& action);

}  // namespace anascan::gui
