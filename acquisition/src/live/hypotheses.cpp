// LiveRegistrar: the hypotheses for a new scan (motion prior, previous pose, global) and the
// group model they are verified against.
#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <string>

#include "anascan/processing/core/median.hpp"
#include "anascan/processing/spatial/kdtree.hpp"
#include "live/state.hpp"
#include "live/votes.hpp"

namespace anascan::acquisition {
namespace {

using live::ScanEntry;
using live::Verified;
using Clock = std::chrono::steady_clock;

/// Sensor position of `entry` in its group's frame under `T_group_scan`.
Eigen::Vector3d sensor_in_group(const ScanEntry& entry, const Pose& T_group_scan) {
    return T_group_scan * entry.sensor_origin_m;
}

LiveAttempt attempt_of(LiveHypothesis method, const Verified& v, std::int64_t target_seq,
                       int group) {
    return {.method = method,
            .status = v.rejection.empty() ? "verified" : v.rejection,
            .target_seq = target_seq,
            .target_group = group,
            .rms_m = v.fine.rms_m,
            .overlap_fraction = v.fine.overlap_fraction,
            .time_s = v.fine.time_s};
}

}  // namespace

std::string LiveRegistrar::State::correction_problem(const ScanEntry& entry, const Pose& T_prior,
                                                     const FineRegistrationResult& fine,
                                                     live::CorrectionCheck check) const {
    const double rotation_deg = rotation_angle_deg(T_prior.inverse() * fine.T_target_source);
    const double moved_m =
        (T_prior * entry.centroid_m - fine.T_target_source * entry.centroid_m).norm();
    if (rotation_deg <= config.hypotheses.max_prior_correction_deg &&
        moved_m <= config.hypotheses.max_prior_correction_m) {
        return {};
    }
    const bool within_fitting_bounds =
        rotation_deg <= config.hypotheses.max_fitting_correction_deg &&
        moved_m <= config.hypotheses.max_fitting_correction_m;
    if (check == live::CorrectionCheck::kBoundOrFit && within_fitting_bounds &&
        accepted_rms_m.size() >= config.verify.min_accepted_for_limits &&
        fine.rms_m <= config.hypotheses.fitting_correction_factor * upper_median(accepted_rms_m) &&
        fine.normal_deviation_deg.value_or(0.0) <=
            config.hypotheses.fitting_correction_factor * upper_median(accepted_normal_deviation)) {
        return {};
    }
    return "moved too far from the hypothesis";
}

std::vector<live::Prior> live::motion_priors(const std::vector<Pose>& recent) {
    // Walking around the stone moves the sensor by a rotation about the stone's vertical
    // axis (world frame): repeat the last step (constant velocity), or the last double step
    // applied to the scan before last (elevations alternating between two heights).
    std::vector<live::Prior> hypotheses;
    if (recent.empty()) return hypotheses;
    if (recent.size() >= 2) {
        hypotheses.emplace_back(LiveHypothesis::kMotionPrior,
                                orthonormalized(recent[0] * recent[1].inverse() * recent[0]));
    }
    if (recent.size() >= 3) {
        hypotheses.emplace_back(LiveHypothesis::kMotionPrior2,
                                orthonormalized(recent[0] * recent[2].inverse() * recent[1]));
    }
    hypotheses.emplace_back(LiveHypothesis::kPreviousPose, recent[0]);
    return hypotheses;
}

void LiveRegistrar::State::probe_slides(const ScanEntry& entry, const PointCloud& model,
                                        const KdTree& tree, Verified& v) const {
    // Periodic relief (an ornament band) or a long edge lets the scan slide along the
    // weakest direction into another minimum: restart from a few shifts along it and keep
    // the verified pose with the largest overlap.
    const Eigen::Vector3d weak = v.fine.degeneracy.weakest_direction.tail<3>();
    if (config.hypotheses.slide_probe_m <= 0.0 || weak.norm() < 0.7) return;
    const Pose T_found = v.fine.T_target_source;
    for (const double k : {-1.0, 1.0}) {
        const Pose T_start =
            Eigen::Translation3d(k * config.hypotheses.slide_probe_m * weak.normalized()) * T_found;
        FineRegistrationResult fine =
            register_fine(entry.cloud, model, tree, T_start, config.hypotheses.fine);
        if (!live::rejection(fine, config, limits()).empty()) continue;
        if (fine.overlap_fraction >
            v.fine.overlap_fraction + config.hypotheses.slide_overlap_margin) {
            v.fine = std::move(fine);
        }
    }
}

std::vector<std::size_t> LiveRegistrar::State::members(int group) const {
    std::vector<std::size_t> out;
    for (std::size_t i = scans.size(); i-- > 0;) {
        const ScanEntry& e = scans[i];
        if (live::active(e) && e.group == group) out.push_back(i);
    }
    return out;
}

std::map<int, std::vector<std::size_t>> LiveRegistrar::State::group_members() const {
    std::map<int, std::vector<std::size_t>> out;
    for (std::size_t i = scans.size(); i-- > 0;) {
        if (live::active(scans[i])) out[scans[i].group].push_back(i);
    }
    return out;
}

std::vector<int> LiveRegistrar::State::groups() const {
    std::set<int> ids;
    for (const ScanEntry& e : scans) {
        if (live::active(e)) ids.insert(e.group);
    }
    return {ids.begin(), ids.end()};
}

const ScanFeatures& LiveRegistrar::State::features(std::size_t i) {
    ScanEntry& entry = scans[i];
    if (entry.features) return *entry.features;
    if (!radii_m) {
        const bool automatic =
            std::all_of(config.global.radii_m.begin(), config.global.radii_m.end(),
                        [](double r) { return r == 0.0; });
        radii_m = automatic ? radii_for_object_size_m(local_bounds(entry.cloud).extent().norm())
                            : config.global.radii_m;
    }
    IntegralInvariantResult invariants =
        describe_scan(entry.cloud, *radii_m, config.global.registration);
    if (!levels && invariants.status == IntegralInvariantStatus::kOk) {
        const IntegralInvariantResult* const first[] = {&invariants};
        levels = saliency_levels(first, config.global.registration.patches);
    }
    ScanFeatures f;
    if (levels && invariants.status == IntegralInvariantStatus::kOk) {
        f.patches =
            extract_feature_patches(invariants, *levels, config.global.registration.patches);
    }
    f.invariants = std::move(invariants);
    f.spacing_m = median_sample_spacing_m(entry.cloud);
    entry.features = std::move(f);
    return *entry.features;
}

const live::ModelCache& LiveRegistrar::State::model_of(
    int group, const std::vector<std::size_t>& candidates) const {
    // Hypotheses of one scan, and consecutive scans, mostly share their model: rebuild it
    // (and its k-d tree) only when the scans or their poses changed.
    std::vector<Pose> poses;
    for (std::size_t i : candidates) poses.push_back(scans[i].T_group_scan);
    live::ModelCache& cache = model_cache;
    const bool same =
        cache.tree && cache.group == group && cache.scans == candidates &&
        std::equal(poses.begin(), poses.end(), cache.poses.begin(),
                   [](const Pose& a, const Pose& b) { return a.matrix() == b.matrix(); });
    if (same) return cache;
    cache = {};
    for (std::size_t i : candidates)
        append(cache.cloud, transformed(scans[i].cloud, scans[i].T_group_scan));
    cache.tree = std::make_unique<KdTree>(cache.cloud.positions);
    cache.group = group;
    cache.scans = candidates;
    cache.poses = std::move(poses);
    return cache;
}

live::Verified LiveRegistrar::State::verify_hypothesis(const ScanEntry& entry, int group,
                                                       const Pose& T_group_scan,
                                                       live::CorrectionCheck check) const {
    // The model: the group's scans whose sensors stood nearest the hypothesis's sensor.
    std::vector<std::size_t> candidates = members(group);
    const Eigen::Vector3d sensor = sensor_in_group(entry, T_group_scan);
    std::stable_sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
        return (sensor_in_group(scans[a], scans[a].T_group_scan) - sensor).squaredNorm() <
               (sensor_in_group(scans[b], scans[b].T_group_scan) - sensor).squaredNorm();
    });
    if (candidates.size() > config.hypotheses.model_scans)
        candidates.resize(config.hypotheses.model_scans);
    std::sort(candidates.begin(), candidates.end());  // The same set: the same cached model.
    Verified v;
    if (candidates.empty()) {
        v.rejection = "empty model";
        return v;
    }
    const live::ModelCache& cache = model_of(group, candidates);
    const PointCloud& model = cache.cloud;
    const KdTree& tree = *cache.tree;
    v.fine = register_fine(entry.cloud, model, tree, T_group_scan, config.hypotheses.fine);
    v.rejection = live::rejection(v.fine, config, limits());
    const auto check_correction = [&] {
        if (check != live::CorrectionCheck::kNone && v.rejection.empty())
            v.rejection = correction_problem(entry, T_group_scan, v.fine, check);
    };
    check_correction();
    if (!v.rejection.empty()) return v;
    probe_slides(entry, model, tree, v);
    check_correction();
    return v;
}

live::VerificationLimits LiveRegistrar::State::limits() const {
    live::VerificationLimits out{
        .max_rms_m = config.verify.max_rms_voxel_factor * config.prepare.voxel_size_m,
        .max_normal_deviation_deg = config.verify.max_normal_deviation_deg};
    if (accepted_rms_m.size() < config.verify.min_accepted_for_limits) return out;
    out.max_rms_m = std::min(out.max_rms_m, std::max(config.verify.min_rms_limit_m,
                                                     config.verify.accepted_rms_median_factor *
                                                         upper_median(accepted_rms_m)));
    out.max_normal_deviation_deg = std::min(out.max_normal_deviation_deg,
                                            std::max(config.verify.min_normal_deviation_limit_deg,
                                                     config.verify.accepted_normal_median_factor *
                                                         upper_median(accepted_normal_deviation)));
    return out;
}

double LiveRegistrar::State::rms_gate() const {
    if (link_rms_m.size() < config.global.min_links_for_rms_gate) {
        return std::numeric_limits<double>::infinity();
    }
    return config.global.rms_median_factor * upper_median(link_rms_m);
}

std::vector<live::Prior> LiveRegistrar::State::priors(std::int64_t seq, int& group) const {
    std::vector<live::Prior> hypotheses;
    if (awaiting_turn) return hypotheses;
    // The latest registered scan's group is where the operator is working.
    std::optional<std::size_t> latest;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (live::active(scans[i]) && scans[i].seq != seq) latest = i;
    }
    if (!latest) return hypotheses;
    group = scans[*latest].group;
    std::vector<Pose> recent;
    for (std::size_t i : members(group)) {
        if (recent.size() == 3) break;
        recent.push_back(scans[i].T_group_scan);
    }
    hypotheses = live::motion_priors(recent);
    if (hypotheses.size() == 3 && last_prior == LiveHypothesis::kMotionPrior2)
        std::swap(hypotheses[0], hypotheses[1]);
    return hypotheses;
}

std::optional<live::Verified> LiveRegistrar::State::try_cheap(const ScanEntry& entry, int& group,
                                                              LiveMethod& method,
                                                              LiveDecision& decision) const {
    const auto hypotheses = priors(entry.seq, group);
    for (const auto& [name, T] : hypotheses) {
        const Clock::time_point start = Clock::now();
        Verified v = verify_hypothesis(entry, group, T, live::CorrectionCheck::kBoundOrFit);
        decision.attempts.push_back(attempt_of(name, v, scans[members(group)[0]].seq, group));
        decision.attempts.back().time_s = seconds_since(start);  // Model, fine and probes.
        if (v.rejection.empty()) {
            method = name == LiveHypothesis::kPreviousPose ? LiveMethod::kPreviousPose
                                                           : LiveMethod::kMotionPrior;
            last_prior = name;
            return v;
        }
    }
    return std::nullopt;
}

std::vector<std::size_t> LiveRegistrar::State::global_targets(std::size_t entry_index) const {
    std::vector<std::size_t> targets;
    for (std::size_t i = scans.size(); i-- > 0;) {
        if (i != entry_index && live::active(scans[i])) targets.push_back(i);
    }
    if (targets.size() > config.global.max_targets) targets.resize(config.global.max_targets);
    return targets;
}

const HypothesisOutcome* LiveRegistrar::State::vote(const GlobalRegistrationResult& g,
                                                    std::size_t target, const ScanEntry& entry,
                                                    const std::vector<live::Prior>& near_priors,
                                                    live::PoseVotes& box) const {
    // A verified pose near the operator's predicted one settles the ambiguity (the largest
    // overlap among them); otherwise verified poses within the session's RMS gate vote.
    const HypothesisOutcome* near_prior = nullptr;
    for (const HypothesisOutcome& h : g.hypotheses) {
        if (!h.verified || h.fine.rms_m > rms_gate()) continue;
        const Pose T = scans[target].T_group_scan * h.fine.T_target_source;
        const bool near = std::any_of(near_priors.begin(), near_priors.end(), [&](const auto& p) {
            return live::poses_agree(p.second, T, entry.centroid_m, config.global.max_prior_deg,
                                     config.global.max_prior_m);
        });
        if (near && (!near_prior || h.fine.overlap_fraction > near_prior->fine.overlap_fraction))
            near_prior = &h;
        box.add(T, target, entry.centroid_m);
    }
    return near_prior;
}

std::optional<Pose> LiveRegistrar::State::global_pose(std::size_t entry_index, int& group,
                                                      LiveDecision& decision) {
    int prior_group = -1;
    const std::vector<live::Prior> hypotheses = priors(scans[entry_index].seq, prior_group);
    const ScanFeatures& source_f = features(entry_index);
    std::map<int, live::PoseVotes> votes;
    for (std::size_t t : global_targets(entry_index)) {
        const Clock::time_point start = Clock::now();
        const GlobalRegistrationResult g =
            register_global(scans[entry_index].cloud, source_f, scans[t].cloud, features(t),
                            config.global.registration);
        decision.attempts.push_back({.method = LiveHypothesis::kGlobal,
                                     .status = std::string(to_string(g.status)),
                                     .target_seq = scans[t].seq,
                                     .target_group = scans[t].group,
                                     .rms_m = g.rms_m,
                                     .overlap_fraction = g.overlap_fraction,
                                     .time_s = seconds_since(start)});
        const int g_id = scans[t].group;
        auto& box = votes.try_emplace(g_id, config.votes.rotation_deg, config.votes.displacement_m)
                        .first->second;
        const std::vector<live::Prior> none;
        const HypothesisOutcome* near =
            vote(g, t, scans[entry_index], g_id == prior_group ? hypotheses : none, box);
        if (near) {
            group = g_id;
            decision.attempts.back().status = "verified near a prior";
            return scans[t].T_group_scan * near->fine.T_target_source;
        }
        // A group too small to vote (e.g. the one scan after a turn-over) takes a success.
        if (g.status == GlobalRegistrationStatus::kSuccess && g.rms_m <= rms_gate() &&
            members(g_id).size() < config.votes.min_count) {
            group = g_id;
            return scans[t].T_group_scan * g.T_target_source;
        }
        if (const std::optional<Pose> T = box.winner(config.votes.min_count, config.votes.ratio)) {
            group = g_id;
            decision.attempts.back().status = "verified by votes";
            return T;
        }
    }
    return std::nullopt;
}

std::optional<live::Verified> LiveRegistrar::State::try_global(std::size_t entry_index, int& group,
                                                               LiveDecision& decision) {
    const std::optional<Pose> T = global_pose(entry_index, group, decision);
    if (!T) return std::nullopt;
    // Refine against the group's model for the same figures as the cheap path.
    Verified v = verify_hypothesis(scans[entry_index], group, *T);
    decision.attempts.push_back(attempt_of(LiveHypothesis::kGlobalModel, v, -1, group));
    if (!v.rejection.empty()) return std::nullopt;
    return v;
}

}  // namespace anascan::acquisition
