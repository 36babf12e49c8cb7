// register_scans: prepare → pairwise global registration → pose graph → links → multi-view.
#include "anascan/processing/registration/batch/scan_registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>

#include "anascan/processing/core/stopwatch.hpp"
#include "anascan/processing/spatial/voxel_grid.hpp"
#include "registration/batch/steps.hpp"
#include "registration/global/steps.hpp"

namespace anascan {

namespace {

void report(const RegistrationProgress& progress, const std::string& message) {
    if (progress) progress(message);
}

/// Weight of a verified pair in the maximum spanning tree (higher is better).
double pair_weight(const GlobalRegistrationResult& global) {
    const double spacing = std::max(global.target_spacing_m, 1e-9);
    return global.overlap_fraction / (1.0 + global.rms_m / spacing);
}

bool features_usable(const ScanFeatures& f) {
    return f.invariants.status == IntegralInvariantStatus::kOk &&
           f.patches.status == FeaturePatchStatus::kOk;
}

/// What the pairwise stages share: the prepared scans, the matchings (record p belongs to
/// pair p, on file when spilling), the config, the pairs so far and the progress callback.
struct PairStages {
    detail::PreparedScans& scans;
    detail::RecordFile& matchings;
    const ScanRegistrationConfig& config;
    std::vector<PairOutcome>& pairs;
    const RegistrationProgress& progress;
};

/// Feature matching of the pairs to match (source = the later scan); one record per pair,
/// in pair order, appended to the pairs and to the matchings.
void match_pairs(PairStages& s,
                 const std::vector<std::pair<std::size_t, std::size_t>>& candidates) {
    std::size_t reported = s.scans.size();
    FeaturePatchResult source_patches;
    for (const auto& [source, target] : candidates) {
        if (source != reported) {
            report(s.progress, "matching scan " + std::to_string(source) + " with earlier scans");
            reported = source;
            source_patches = s.scans.patches(source);
        }
        PairOutcome pair{.source = source, .target = target};
        FeatureMatchingResult matching;
        if (features_usable(s.scans.features[source]) &&
            features_usable(s.scans.features[target])) {
            matching =
                match_features(source_patches, s.scans.patches(target), s.config.global.matching);
            pair.hypotheses = matching.hypotheses.size();
            if (!matching.hypotheses.empty()) pair.match_score = matching.hypotheses.front().score;
            pair.global.status = GlobalRegistrationStatus::kNoConsensus;
        }
        s.pairs.push_back(pair);
        s.matchings.append(detail::to_bytes(matching));
    }
}

void copy_global_figures(const GlobalRegistrationResult& g, PairOutcome& pair) {
    pair.global.status = g.status;
    pair.verified = g.status == GlobalRegistrationStatus::kSuccess;
    pair.weight = pair.verified ? pair_weight(g) : 0.0;
    pair.T_target_source = g.T_target_source;
    pair.global.rms_m = g.rms_m;
    pair.global.target_spacing_m = g.target_spacing_m;
    pair.global.overlap_fraction = g.overlap_fraction;
    pair.global.time_s = g.timing.total_s;
    pair.free_space_rejections = g.free_space_rejections;
    pair.slides.probes = g.slide_probes;
    pair.slides.ambiguous = g.slide_ambiguous;
    pair.slides.slide_m = g.slide_m;
}

/// The matched pairs from `first` on not refined yet, best consensus score first.
std::vector<std::size_t> refinement_order(const std::vector<PairOutcome>& pairs,
                                          std::size_t first) {
    std::vector<std::size_t> order;
    for (std::size_t p = first; p < pairs.size(); ++p) {
        if (pairs[p].hypotheses > 0 && !pairs[p].global.refined) order.push_back(p);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return pairs[a].match_score > pairs[b].match_score;
    });
    return order;
}

/// Refines and verifies pair p (record p of the matchings) under the RMS gate `gate_m`.
void refine_pair(PairStages& s, std::size_t p, double gate_m) {
    PairOutcome& pair = s.pairs[p];
    const std::shared_ptr<const PointCloud> source = s.scans.cloud(pair.source);
    const std::shared_ptr<const PointCloud> target = s.scans.cloud(pair.target);
    const ScanFeatures source_f = s.scans.full_features(pair.source);
    const ScanFeatures target_f = s.scans.full_features(pair.target);
    const GlobalRegistrationResult g =
        detail::refine_and_verify({*source, source_f, s.scans.viewpoint_m[pair.source]},
                                  {*target, target_f, s.scans.viewpoint_m[pair.target]},
                                  detail::matching_from(s.matchings.read(p)), s.config.global);
    copy_global_figures(g, pair);
    pair.global.refined = true;
    detail::apply_rms_gate(pair, gate_m);
}

void report_refined(PairStages& s, const PairOutcome& pair, std::size_t tried) {
    report(s.progress, "global registration " + std::to_string(tried) + ": scan " +
                           std::to_string(pair.source) + " onto " + std::to_string(pair.target) +
                           " (score " + std::to_string(static_cast<int>(pair.match_score)) +
                           "): " + std::string(to_string(pair.global.status)) +
                           (pair.above_rms_gate ? " above the session RMS gate" : ""));
}

/// Refines and verifies the matched pairs from `first` on not refined yet, best consensus
/// score first, until their scans are connected through verified pairs (those before
/// `first` included); pairs of connected scans are skipped unless `every_pair`, and so are
/// the pairs of a scan that failed max_failed_refinements_per_scan times. A pair verified
/// with an RMS above `gate_m` does not count (apply_rms_gate).
void verify_pairs(PairStages& s, std::size_t first, double gate_m, bool every_pair = false) {
    detail::DisjointSets connected(s.scans.size());
    for (const PairOutcome& pair : s.pairs) {
        if (pair.verified) connected.unite(pair.source, pair.target);
    }
    std::vector<std::size_t> failures(s.scans.size(), 0);
    const std::size_t max_failures = s.config.max_failed_refinements_per_scan;
    const auto gave_up = [&](std::size_t i) {
        return max_failures > 0 && failures[i] >= max_failures;
    };
    std::size_t tried = 0;
    for (std::size_t p : refinement_order(s.pairs, first)) {
        PairOutcome& pair = s.pairs[p];
        pair.global.skipped =
            (!every_pair && connected.find(pair.source) == connected.find(pair.target)) ||
            gave_up(pair.source) || gave_up(pair.target);
        if (pair.global.skipped) continue;
        refine_pair(s, p, gate_m);
        if (pair.verified) {
            connected.unite(pair.source, pair.target);
        } else {
            ++failures[pair.source];
            ++failures[pair.target];
        }
        report_refined(s, pair, ++tried);
    }
}

/// Whether the first pairwise pass refines every matched pair (see
/// ScanRegistrationConfig::full_pairwise_max_scans).
bool every_pair_before_gate(const detail::PreparedScans& scans,
                            const ScanRegistrationConfig& config) {
    if (scans.size() > config.full_pairwise_max_scans) return false;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (scans.usable(i) && !scans.viewpoint_m[i]) return false;
    }
    return true;
}

/// The session RMS gate: un-verifies the verified pairs above it, then refines (under the
/// gate) the pairs skipped so far. Returns the gate (metres; infinity when off).
double gate_pairs(PairStages& s) {
    const double gate_m = detail::session_rms_gate_m(s.pairs, s.scans.size(), s.config);
    std::size_t rejected = 0;
    for (PairOutcome& pair : s.pairs) rejected += detail::apply_rms_gate(pair, gate_m);
    if (rejected == 0) return gate_m;
    report(s.progress, "session RMS gate " + std::to_string(gate_m * 1e3) +
                           " mm: " + std::to_string(rejected) + " verified pairs above it");
    verify_pairs(s, 0, gate_m);
    return gate_m;
}

/// The pairwise stage: every matched pair refined and verified until the scans connect,
/// then the session RMS gate. Returns the gate (metres; infinity when off).
double verify_and_gate(PairStages& s) {
    verify_pairs(s, 0, std::numeric_limits<double>::infinity(),
                 every_pair_before_gate(s.scans, s.config));
    return gate_pairs(s);
}

/// Bridging rounds (pruning only): while the verified pairs leave several groups, matches
/// and verifies each smaller group's most similar pairs with other groups not matched yet.
/// Returns the number of pairs added.
std::size_t bridge_groups(PairStages& s, const detail::CandidatePairs& candidates,
                          const std::vector<bool>& usable, double gate_m) {
    if (candidates.votes.n == 0 || s.config.bridge_partners_per_scan == 0) return 0;
    std::set<std::pair<std::size_t, std::size_t>> matched(candidates.pairs.begin(),
                                                          candidates.pairs.end());
    std::size_t added = 0;
    for (std::size_t round = 0; round < s.config.bridge_rounds; ++round) {
        const detail::PoseGraph graph = detail::build_pose_graph(usable, s.pairs);
        if (graph.group_count <= 1) break;
        const std::vector<std::pair<std::size_t, std::size_t>> extra =
            detail::bridge_pairs(candidates.votes, graph, s.scans.summary, matched, s.config);
        if (extra.empty()) break;
        report(s.progress, "bridging round " + std::to_string(round + 1) + ": " +
                               std::to_string(graph.group_count) + " groups, " +
                               std::to_string(extra.size()) + " more pairs");
        const std::size_t first = s.pairs.size();
        match_pairs(s, extra);
        verify_pairs(s, first, gate_m);
        matched.insert(extra.begin(), extra.end());
        added += extra.size();
    }
    return added;
}

/// Why scan i is not in the largest group: what its pairs gave.
std::string not_connected_reason(const ScanRegistrationResult& result, std::size_t i) {
    std::size_t matched = 0, refined = 0, verified = 0, gated = 0, free_space = 0, slid = 0;
    double slide_m = 0.0;
    for (const PairOutcome& p : result.pairs) {
        if (p.source != i && p.target != i) continue;
        matched += p.hypotheses > 0;
        refined += p.global.refined;
        verified += p.verified;
        gated += p.above_rms_gate;
        free_space += p.free_space_rejections > 0;
        slid += p.slides.ambiguous;
        if (p.slides.ambiguous) slide_m = std::max(slide_m, p.slides.slide_m);
    }
    std::string reason = "no verified chain of pairs to the largest group (in group " +
                         std::to_string(result.scans[i].group) + "): ";
    if (matched == 0) return reason + "no other scan shares consistent features with it";
    return reason + std::to_string(matched) + " pairs with consistent features, " +
           std::to_string(refined) + " refined, " + std::to_string(verified) + " verified" +
           (gated > 0 ? ", " + std::to_string(gated) +
                            " verified alone but above the session RMS gate (look-alike poses?)"
                      : "") +
           (free_space > 0 ? ", " + std::to_string(free_space) +
                                 " with poses rejected by the free-space check (look-alike poses "
                                 "putting points where the other sensor saw empty space)"
                           : "") +
           (slid > 0 ? ", " + std::to_string(slid) + " ambiguous along a slide of up to " +
                           std::to_string(static_cast<int>(slide_m * 1e3 + 0.5)) +
                           " mm (the overlap does not fix the pose along it)"
                     : "");
}

/// Copies the graph's groups and poses into the outcomes and counts.
void place_scans(const detail::PoseGraph& graph, ScanRegistrationResult& result) {
    bool reference_found = false;
    for (std::size_t i = 0; i < result.scans.size(); ++i) {
        ScanOutcome& scan = result.scans[i];
        scan.group = graph.group[i];
        if (scan.group < 0) continue;
        scan.T_world_scan = graph.T_root_scan[i];
        scan.placed = scan.group == 0;
        if (!scan.placed) scan.reason = not_connected_reason(result, i);
        if (scan.placed && !reference_found) {
            result.reference_scan = i;
            reference_found = true;
        }
        result.placed_count += scan.placed;
    }
    result.group_count = graph.group_count;
}

/// Runs `stage` and adds the seconds it took to `seconds`; returns what it returns.
template <class Stage>
decltype(auto) timed(double& seconds, Stage&& stage) {
    ScopedTimer timer(seconds);
    return stage();
}

std::vector<bool> usable_scans(const detail::PreparedScans& prepared) {
    std::vector<bool> usable(prepared.size());
    for (std::size_t i = 0; i < prepared.size(); ++i) usable[i] = prepared.usable(i);
    return usable;
}

std::filesystem::path matchings_path(const ScanRegistrationConfig& config) {
    return config.spill_directory.empty() ? std::filesystem::path()
                                          : config.spill_directory / "matchings.bin";
}

/// The counts over the pairs and the first spill failure, after the pairwise stages.
void count_pairs(detail::PreparedScans& prepared, const detail::RecordFile& matchings,
                 ScanRegistrationResult& result) {
    if (!matchings.error().empty() && prepared.spill_error.empty()) {
        prepared.spill_error = matchings.error();
    }
    for (const PairOutcome& p : result.pairs) {
        result.verified_pair_count += p.verified;
        result.gated_pair_count += p.above_rms_gate;
    }
}

/// Links and multi-view refinement of each group of `graph`.
void refine_views(PairStages& s, detail::PoseGraph& graph, ScanRegistrationResult& result) {
    detail::PairLinks links = timed(result.timings.fine_s, [&] {
        return detail::make_links(s.scans, graph, s.pairs, s.config, s.progress);
    });
    result.link_count = links.links.size();
    ScopedTimer timer(result.timings.multiview_s);
    report(s.progress,
           "multi-view refinement over " + std::to_string(result.link_count) + " links");
    result.multiview_status =
        detail::refine_groups(std::move(links), s.config.multiview, graph, s.pairs);
    for (const PairOutcome& p : s.pairs) result.dropped_link_count += p.link_dropped;
}

/// Places the scans of the graph's groups and adds the warnings.
void finish(detail::PreparedScans& prepared, const detail::PoseGraph& graph,
            const ScanRegistrationConfig& config, ScanRegistrationResult& result) {
    place_scans(graph, result);
    detail::warn_identical_scans(prepared, result);
    detail::warn_sliding_scans(config, result);
    detail::warn_unconfirmed_scans(result);
    result.cloud_reloads = prepared.store.reload_count();
    result.spill_error = prepared.spill_error;
}

}  // namespace

ScanRegistrationResult register_scans(const std::vector<ScanInput>& scans,
                                      const ScanRegistrationConfig& config,
                                      const RegistrationProgress& progress) {
    const Stopwatch total;
    ScanRegistrationResult result;
    ScanRegistrationTimings& time = result.timings;
    for (const ScanInput& input : scans) result.scans.push_back({.name = input.name});
    detail::PreparedScans prepared = timed(
        time.prepare_s, [&] { return detail::load_and_prepare(scans, config, progress, result); });
    const std::vector<bool> usable = usable_scans(prepared);
    timed(time.features_s, [&] { detail::describe_all(prepared, config, progress); });
    detail::RecordFile matchings(matchings_path(config));
    PairStages stages{prepared, matchings, config, result.pairs, progress};
    detail::CandidatePairs candidates = timed(time.matching_s, [&] {
        detail::CandidatePairs pairs = detail::candidate_pairs(prepared, config);
        match_pairs(stages, pairs.pairs);
        return pairs;
    });
    result.session_rms_gate_m = timed(time.pairwise_s, [&] { return verify_and_gate(stages); });
    result.bridge_pair_count = timed(time.bridging_s, [&] {
        return bridge_groups(stages, candidates, usable, result.session_rms_gate_m);
    });
    count_pairs(prepared, matchings, result);
    candidates = {};  // The pruning votes (N²/2 floats) are not needed any more.
    detail::PoseGraph graph =
        timed(time.pose_graph_s, [&] { return detail::build_pose_graph(usable, result.pairs); });
    refine_views(stages, graph, result);
    finish(prepared, graph, config, result);
    time.total_s = total.seconds();
    return result;
}

}  // namespace anascan
