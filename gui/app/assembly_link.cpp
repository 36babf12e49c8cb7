#include "assembly_link.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "anascan/acquisition/blocks/block_folder.hpp"
#include "future_ready.hpp"
#include "thread_priority.hpp"

namespace anascan::field {
namespace {

namespace acq = acquisition;
namespace ra = reassembly;

std::vector<gui::AssemblyFaceRow> proposal_rows(const acq::BlockProposals& proposals) {
    std::vector<gui::AssemblyFaceRow> rows;
    for (const acq::FaceProposals& f : proposals.faces) {
        gui::AssemblyFaceRow& row = rows.emplace_back();
        row.face = f.face;
        for (const acq::ProposalCandidate& c : f.candidates) {
            std::string names;
            for (const std::string& n : c.passed) names += (names.empty() ? "" : ", ") + n;
            row.candidates.push_back({.face = c.face,
                                      .score = c.score,
                                      .passed = c.passed.size(),
                                      .checks = c.checks,
                                      .passed_names = names,
                                      .accepted = c.accepted,
                                      .neighbour_pairs = c.neighbour_pairs});
        }
    }
    return rows;
}

gui::AssemblyReportView report_view(const acq::BlockAlignment& a) {
    gui::AssemblyReportView out{.status = ra::to_string(a.result.status),
                                .message = a.result.message,
                                .offending = a.result.offending,
                                .iterations = a.result.iterations,
                                .seconds = a.seconds,
                                .penetration_max_mm = 1e3 * a.check.penetration_max_m,
                                .penetration_mean_mm = 1e3 * a.check.penetration_mean_m,
                                .penetrating_points = a.check.penetrating_points};
    for (const ra::ContactCheck& c : a.check.contacts)
        out.pairs.push_back({.pair = c.pair,
                             .gap_median_mm = 1e3 * c.gap_median_m,
                             .gap_p95_mm = 1e3 * c.gap_p95_m,
                             .gap_min_mm = 1e3 * c.gap_min_m});
    for (const ra::CoplanarCheck& c : a.check.coplanar)
        out.coplanar.push_back(
            {.pair = c.pair, .angle_deg = c.angle_deg, .offset_mm = 1e3 * c.offset_m});
    return out;
}

/// The face of point i, or where it has none (an arris, a chip, the recess of a joint face)
/// the face of the nearest point within 20 mm that has one; -1 when none has.
int face_near(const ra::AssemblyBlock& block, std::size_t i) {
    const std::vector<int>& face = block.features.point_face;
    if (face[i] >= 0) return face[i];
    constexpr float kReach = 0.02f;
    const Eigen::Vector3f& x = block.points.positions[i];
    int best = -1;
    float best_d2 = kReach * kReach;
    for (std::size_t j = 0; j < face.size(); ++j) {
        const float d2 = (block.points.positions[j] - x).squaredNorm();
        if (face[j] >= 0 && d2 < best_d2) {
            best = face[j];
            best_d2 = d2;
        }
    }
    return best;
}

bool fixed_block(const AssemblyLinkConfig& c, const std::string& id, std::size_t index) {
    if (c.fixed.empty()) return index == 0;
    return std::find(c.fixed.begin(), c.fixed.end(), id) != c.fixed.end();
}

}  // namespace

AssemblyLink::AssemblyLink(AssemblyLinkConfig config) : config_(std::move(config)) {}

AssemblyLink::~AssemblyLink() {
    if (loading_) loading_->wait();
    if (aligning_) aligning_->wait();
    if (saving_) saving_->wait();
}

void AssemblyLink::open(gui::AssemblyViewState& view) {
    view.folder = config_.dir.string();
    auto folder = acq::open_block_folder(config_.dir);
    if (!folder) {
        view.phase = gui::AssemblyPhase::kFailed;
        view.last_error = folder.error().message;
        return;
    }
    folder_ = std::move(*folder);
    for (std::size_t b = 0; b < folder_->ids.size(); ++b)
        view.blocks.push_back({.id = folder_->ids[b],
                               .colour = acq::block_colour(b),
                               .fixed = fixed_block(config_, folder_->ids[b], b)});
    const std::filesystem::path proposals =
        config_.proposals.value_or(config_.dir / "proposals.json");
    if (config_.proposals || std::filesystem::exists(proposals)) {
        auto read = acq::read_block_proposals(proposals);
        if (read) {
            view.proposals = proposal_rows(*read);
            accepted_ = acq::accepted_pairs(*read);
        } else {
            view.last_error = read.error().message;
        }
    }
    view.phase = gui::AssemblyPhase::kLoading;
    view.progress = fmt::format("Loading {} blocks", folder_->ids.size());
    loading_ = std::async(
        std::launch::async, [folder = *folder_, progress = progress_, nice = config_.worker_nice] {
            lower_this_thread_priority(nice);
            return acq::load_folder_blocks(folder, [&](std::size_t done, std::size_t all) {
                const std::lock_guard lock(progress->mutex);
                progress->text = fmt::format("Loading block {} of {} (model and features)",
                                             std::min(done + 1, all), all);
            });
        });
}

void AssemblyLink::take_loaded(gui::AssemblyViewState& view, gui::PointRenderer& renderer) {
    auto blocks = loading_->get();
    loading_.reset();
    view.progress.clear();
    if (!blocks) {
        view.phase = gui::AssemblyPhase::kFailed;
        view.last_error = blocks.error().message;
        return;
    }
    blocks_ = std::make_shared<const Blocks>(std::move(*blocks));
    show_blocks(renderer);
    view.phase = gui::AssemblyPhase::kReady;
}

// Every block where its model lies, in its colour; the aligned ones at their assembled
// poses, coloured by gap and penetration.
void AssemblyLink::show_blocks(gui::PointRenderer& renderer) const {
    for (std::size_t b = 0; b < blocks_->size(); ++b) {
        PointCloud cloud;
        cloud.positions = (*blocks_)[b].points.positions;
        cloud.colors.assign(cloud.size(), acq::block_colour(b));
        renderer.add_chunk(std::int64_t(b), std::move(cloud), Eigen::Isometry3d::Identity());
    }
    if (!linked_ || !alignment_) return;
    for (std::size_t k = 0; k < linked_->blocks.size(); ++k) {
        const std::size_t b = linked_->blocks[k];
        renderer.add_chunk(
            std::int64_t(b),
            acq::coloured_block(linked_->problem, alignment_->check, k, acq::block_colour(b)),
            alignment_->result.T_world_block[k]);
    }
}

void AssemblyLink::take_aligned(gui::AssemblyViewState& view, gui::PointRenderer& renderer) {
    auto aligned = aligning_->get();
    aligning_.reset();
    view.progress.clear();
    view.phase = gui::AssemblyPhase::kAligned;
    if (!aligned) {
        view.last_error = aligned.error().message;
        view.phase = gui::AssemblyPhase::kReady;
        return;
    }
    alignment_ = std::move(*aligned);
    view.report = report_view(*alignment_);
    const ra::AssemblyProblem& p = linked_->problem;
    for (gui::AssemblyBlockRow& row : view.blocks) row.fixed = false;
    for (std::size_t k = 0; k < linked_->blocks.size(); ++k)
        view.blocks[linked_->blocks[k]].fixed =
            std::count(p.fixed.begin(), p.fixed.end(), int(k)) > 0 || (p.fixed.empty() && k == 0);
    show_blocks(renderer);
}

Pose AssemblyLink::shown_pose(std::size_t b) const {
    if (linked_ && alignment_)
        for (std::size_t k = 0; k < linked_->blocks.size(); ++k)
            if (linked_->blocks[k] == b) return alignment_->result.T_world_block[k];
    return Pose::Identity();
}

std::string AssemblyLink::pick_face(const gui::ViewRay& ray, double radius_rad) const {
    if (!blocks_) return {};
    std::optional<gui::PickedPoint> best;
    std::size_t best_block = 0;
    for (std::size_t b = 0; b < blocks_->size(); ++b) {
        const auto hit =
            gui::pick_point((*blocks_)[b].points.positions, shown_pose(b), ray, radius_rad);
        if (hit && (!best || hit->depth_m < best->depth_m)) {
            best = hit;
            best_block = b;
        }
    }
    if (!best) return {};
    const ra::AssemblyBlock& block = (*blocks_)[best_block];
    const int face = face_near(block, best->index);
    return face < 0 ? std::string() : block.id + ":" + std::to_string(face);
}

std::optional<Eigen::Vector3d> AssemblyLink::shown_centre(const std::string& id) const {
    if (!blocks_) return std::nullopt;
    for (std::size_t b = 0; b < blocks_->size(); ++b) {
        const PointCloud& points = (*blocks_)[b].points;
        if ((*blocks_)[b].id != id || points.size() == 0) continue;
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (const Eigen::Vector3f& x : points.positions) sum += x.cast<double>();
        return shown_pose(b) * (sum / double(points.size()));
    }
    return std::nullopt;
}

bool AssemblyLink::poll(gui::AssemblyViewState& view, gui::PointRenderer& renderer) {
    if (loading_ || aligning_) {
        const std::lock_guard lock(progress_->mutex);
        if (!progress_->text.empty()) view.progress = progress_->text;
    }
    if (ready(loading_)) {
        take_loaded(view, renderer);
        return true;
    }
    if (ready(aligning_)) {
        take_aligned(view, renderer);
        return true;
    }
    if (ready(saving_)) {
        auto saved = saving_->get();
        saving_.reset();
        view.progress.clear();
        if (saved)
            view.saved_to = config_.out.string();
        else
            view.last_error = saved.error().message;
    }
    return false;
}

void AssemblyLink::start_alignment(gui::AssemblyViewState& view) {
    auto links = acq::parse_assembly_links(
        *folder_,
        {.contacts = view.chosen_pairs, .coplanar = view.chosen_coplanar, .fixed = config_.fixed});
    if (!links) {
        view.last_error = links.error().message;
        return;
    }
    // Only the blocks the pairs name are aligned (copies: the view keeps every block).
    ra::AssemblyProblem whole = std::move(*links);
    whole.blocks = *blocks_;
    linked_ = std::make_shared<const acq::LinkedBlocks>(acq::linked_blocks(whole));
    alignment_.reset();
    view.report.reset();
    view.saved_to.clear();
    view.last_error.clear();
    view.phase = gui::AssemblyPhase::kAligning;
    view.progress = fmt::format("Aligning {} blocks by {} pairs", linked_->blocks.size(),
                                linked_->problem.contacts.size());
    {
        const std::lock_guard lock(progress_->mutex);
        progress_->text.clear();
    }
    aligning_ = std::async(std::launch::async, [linked = linked_, nice = config_.worker_nice] {
        lower_this_thread_priority(nice);
        return acq::align_blocks(linked->problem, {});
    });
}

void AssemblyLink::start_saving(gui::AssemblyViewState& view) {
    view.progress = "Saving to " + config_.out.string();
    saving_ = std::async(std::launch::async, [this, nice = config_.worker_nice] {
        lower_this_thread_priority(nice);
        return acq::write_assembly_folder(config_.out, *folder_, linked_->problem, *alignment_);
    });
}

bool AssemblyLink::apply(const gui::UiAction& action, gui::AssemblyViewState& view) {
    if (action.kind == gui::UiActionKind::kAlignBlocks) {
        if (!blocks_ || !settled())
            view.last_error = "wait: the blocks are still loading or being aligned";
        else if (view.chosen_pairs.empty())
            view.last_error = "choose at least one face pair in the proposals";
        else
            start_alignment(view);
        return true;
    }
    if (action.kind == gui::UiActionKind::kAcceptAssembly) {
        if (!alignment_ || !view.report || !view.report->ok() || !settled())
            view.last_error = "nothing to accept: align first (only an ok alignment is saved)";
        else
            start_saving(view);
        return true;
    }
    return false;
}

}  // namespace anascan::field
