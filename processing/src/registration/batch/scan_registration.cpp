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

/// Feature matching of the pairs to match (source = the later scan); one record per pair,
/// in pair order, appended to `matchings` (a file when spilling).
void match_pairs(detail::PreparedScans& scans,
                 const std::vector<std::pair<std::size_t, std::size_t>>& candidates,
                 const GlobalRegistrationConfig& config, std::vector<PairOutcome>& pairs,
                 detail::RecordFile& matchings, const RegistrationProgress& progress) {
    std::size_t reported = scans.size();
    FeaturePatchResult source_patches;
    for (const auto& [source, target] : candidates) {
        if (source != reported) {
            report(progress, "matching scan " + std::to_string(source) + " with earlier scans");
            reported = source;
            source_patches = scans.patches(source);
        }
        PairOutcome pair{.source = source, .target = target};
        FeatureMatchingResult matching;
        if (features_usable(scans.features[source]) && features_usable(scans.features[target])) {
            matching = match_features(source_patches, scans.patches(target), config.matching);
            pair.hypotheses = matching.hypotheses.size();
            if (!matching.hypotheses.empty()) pair.match_score = matching.hypotheses.front().score;
            pair.global_status = GlobalRegistrationStatus::kNoConsensus;
        }
        pairs.push_back(pair);
        matchings.append(detail::to_bytes(matching));
    }
}

void copy_global_figures(const GlobalRegistrationResult& g, PairOutcome& pair) {
    pair.global_status = g.status;
    pair.verified = g.status == GlobalRegistrationStatus::kSuccess;
    pair.weight = pair.verified ? pair_weight(g) : 0.0;
    pair.T_target_source = g.T_target_source;
    pair.global_rms_m = g.rms_m;
    pair.global_target_spacing_m = g.target_spacing_m;
    pair.global_overlap_fraction = g.overlap_fraction;
    pair.global_time_s = g.timing.total_s;
    pair.free_space_rejections = g.free_space_rejections;
    pair.slide_probes = g.slide_probes;
    pair.slide_ambiguous = g.slide_ambiguous;
    pair.slide_m = g.slide_m;
}

/// Refines and verifies the matched pairs from `first` on (record p of `matchings`) not
/// refined yet, best consensus score first, until their scans are connected through
/// verified pairs (those before `first` included); pairs of connected scans are skipped
/// unless `every_pair`. A pair verified with an RMS above `gate_m` does not count
/// (apply_rms_gate).
void verify_pairs(detail::PreparedScans& scans, detail::RecordFile& matchings, std::size_t first,
                  const ScanRegistrationConfig& config, double gate_m,
                  std::vector<PairOutcome>& pairs, const RegistrationProgress& progress,
                  bool every_pair = false) {
    detail::DisjointSets connected(scans.size());
    std::vector<std::size_t> order;
    std::vector<std::size_t> failures(scans.size(), 0);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        const PairOutcome& pair = pairs[p];
        if (pair.verified) connected.unite(pair.source, pair.target);
        if (p >= first && pair.hypotheses > 0 && !pair.global_refined) order.push_back(p);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return pairs[a].match_score > pairs[b].match_score;
    });
    const std::size_t max_failures = config.max_failed_refinements_per_scan;
    const auto gave_up = [&](std::size_t i) {
        return max_failures > 0 && failures[i] >= max_failures;
    };
    std::size_t tried = 0;
    for (std::size_t p : order) {
        PairOutcome& pair = pairs[p];
        pair.global_skipped =
            (!every_pair && connected.find(pair.source) == connected.find(pair.target)) ||
            gave_up(pair.source) || gave_up(pair.target);
        if (pair.global_skipped) continue;
        const std::shared_ptr<const PointCloud> source = scans.cloud(pair.source);
        const std::shared_ptr<const PointCloud> target = scans.cloud(pair.target);
        const ScanFeatures source_f = scans.full_features(pair.source);
        const ScanFeatures target_f = scans.full_features(pair.target);
        const GlobalRegistrationResult g =
            detail::refine_and_verify({*source, source_f, scans.viewpoint_m[pair.source]},
                                      {*target, target_f, scans.viewpoint_m[pair.target]},
                                      detail::matching_from(matchings.read(p)), config.global);
        copy_global_figures(g, pair);
        pair.global_refined = true;
        detail::apply_rms_gate(pair, gate_m);
        if (pair.verified) {
            connected.unite(pair.source, pair.target);
        } else {
            ++failures[pair.source];
            ++failures[pair.target];
        }
        report(progress, "global registration " + std::to_string(++tried) + ": scan " +
                             std::to_string(pair.source) + " onto " + std::to_string(pair.target) +
                             " (score " + std::to_string(static_cast<int>(pair.match_score)) +
                             "): " + std::string(to_string(pair.global_status)) +
                             (pair.above_rms_gate ? " above the session RMS gate" : ""));
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
double gate_pairs(detail::PreparedScans& scans, detail::RecordFile& matchings,
                  const ScanRegistrationConfig& config, std::vector<PairOutcome>& pairs,
                  const RegistrationProgress& progress) {
    const double gate_m = detail::session_rms_gate_m(pairs, scans.size(), config);
    std::size_t rejected = 0;
    for (PairOutcome& pair : pairs) rejected += detail::apply_rms_gate(pair, gate_m);
    if (rejected == 0) return gate_m;
    report(progress, "session RMS gate " + std::to_string(gate_m * 1e3) +
                         " mm: " + std::to_string(rejected) + " verified pairs above it");
    verify_pairs(scans, matchings, 0, config, gate_m, pairs, progress);
    return gate_m;
}

/// Bridging rounds (pruning only): while the verified pairs leave several groups, matches
/// and verifies each smaller group's most similar pairs with other groups not matched yet.
/// Returns the number of pairs added.
std::size_t bridge_groups(detail::PreparedScans& prepared, const detail::CandidatePairs& candidates,
                          const std::vector<bool>& usable, const ScanRegistrationConfig& config,
                          double gate_m, std::vector<PairOutcome>& pairs,
                          detail::RecordFile& matchings, const RegistrationProgress& progress) {
    if (candidates.votes.n == 0 || config.bridge_partners_per_scan == 0) return 0;
    std::set<std::pair<std::size_t, std::size_t>> matched(candidates.pairs.begin(),
                                                          candidates.pairs.end());
    std::size_t added = 0;
    for (std::size_t round = 0; round < config.bridge_rounds; ++round) {
        const detail::PoseGraph graph = detail::build_pose_graph(usable, pairs);
        if (graph.group_count <= 1) break;
        const std::vector<std::pair<std::size_t, std::size_t>> extra =
            detail::bridge_pairs(candidates.votes, graph, prepared.summary, matched, config);
        if (extra.empty()) break;
        report(progress, "bridging round " + std::to_string(round + 1) + ": " +
                             std::to_string(graph.group_count) + " groups, " +
                             std::to_string(extra.size()) + " more pairs");
        const std::size_t first = pairs.size();
        match_pairs(prepared, extra, config.global, pairs, matchings, progress);
        verify_pairs(prepared, matchings, first, config, gate_m, pairs, progress);
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
        refined += p.global_refined;
        verified += p.verified;
        gated += p.above_rms_gate;
        free_space += p.free_space_rejections > 0;
        slid += p.slide_ambiguous;
        if (p.slide_ambiguous) slide_m = std::max(slide_m, p.slide_m);
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

}  // namespace

ScanRegistrationResult register_scans(const std::vector<ScanInput>& scans,
                                      const ScanRegistrationConfig& config,
                                      const RegistrationProgress& progress) {
    const auto start = std::chrono::steady_clock::now();
    ScanRegistrationResult result;
    for (const ScanInput& input : scans) result.scans.push_back({.name = input.name});
    auto stage = std::chrono::steady_clock::now();
    detail::PreparedScans prepared = detail::load_and_prepare(scans, config, progress, result);
    std::vector<bool> usable(scans.size());
    for (std::size_t i = 0; i < scans.size(); ++i) usable[i] = prepared.usable(i);
    result.timings.prepare_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    detail::describe_all(prepared, config, progress);
    result.timings.features_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    detail::CandidatePairs candidates = detail::candidate_pairs(prepared, config);
    detail::RecordFile matchings(config.spill_directory.empty()
                                     ? std::filesystem::path()
                                     : config.spill_directory / "matchings.bin");
    match_pairs(prepared, candidates.pairs, config.global, result.pairs, matchings, progress);
    result.timings.matching_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    verify_pairs(prepared, matchings, 0, config, std::numeric_limits<double>::infinity(),
                 result.pairs, progress, every_pair_before_gate(prepared, config));
    result.session_rms_gate_m = gate_pairs(prepared, matchings, config, result.pairs, progress);
    result.timings.pairwise_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    result.bridge_pair_count =
        bridge_groups(prepared, candidates, usable, config, result.session_rms_gate_m, result.pairs,
                      matchings, progress);
    if (!matchings.error().empty() && prepared.spill_error.empty()) {
        prepared.spill_error = matchings.error();
    }
    for (const PairOutcome& p : result.pairs) {
        result.verified_pair_count += p.verified;
        result.gated_pair_count += p.above_rms_gate;
    }
    result.timings.bridging_s = seconds_since(stage);
    candidates = {};  // The pruning votes (N²/2 floats) are not needed any more.

    stage = std::chrono::steady_clock::now();
    detail::PoseGraph graph = detail::build_pose_graph(usable, result.pairs);
    result.timings.pose_graph_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    detail::PairLinks links = detail::make_links(prepared, graph, result.pairs, config, progress);
    result.link_count = links.links.size();
    result.timings.fine_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    report(progress, "multi-view refinement over " + std::to_string(result.link_count) + " links");
    result.multiview_status =
        detail::refine_groups(std::move(links), config.multiview, graph, result.pairs);
    for (const PairOutcome& p : result.pairs) result.dropped_link_count += p.link_dropped;
    result.timings.multiview_s = seconds_since(stage);

    place_scans(graph, result);
    detail::warn_identical_scans(prepared, result);
    detail::warn_sliding_scans(config, result);
    result.cloud_reloads = prepared.store.reload_count();
    result.spill_error = prepared.spill_error;
    result.timings.total_s = seconds_since(start);
    return result;
}

}  // namespace anascan
