// register_scans: prepare → pairwise global registration → pose graph → links → multi-view.
#include "anascan/processing/scan_registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "anascan/processing/voxel_grid.hpp"
#include "global_registration_steps.hpp"
#include "scan_registration_steps.hpp"

namespace anascan {
namespace detail {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace detail

namespace {

using detail::seconds_since;

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

/// Feature matching of the pairs to match (source = the later scan); one result per pair,
/// in pair order.
std::vector<FeatureMatchingResult> match_pairs(
    const std::vector<ScanFeatures>& features,
    const std::vector<std::pair<std::size_t, std::size_t>>& candidates,
    const GlobalRegistrationConfig& config, std::vector<PairOutcome>& pairs,
    const RegistrationProgress& progress) {
    std::vector<FeatureMatchingResult> matchings;
    std::size_t reported = features.size();
    for (const auto& [source, target] : candidates) {
        if (source != reported) {
            report(progress, "matching scan " + std::to_string(source) + " with earlier scans");
            reported = source;
        }
        PairOutcome pair{.source = source, .target = target};
        FeatureMatchingResult matching;
        if (features_usable(features[source]) && features_usable(features[target])) {
            matching =
                match_features(features[source].patches, features[target].patches, config.matching);
            pair.hypotheses = matching.hypotheses.size();
            if (!matching.hypotheses.empty()) pair.match_score = matching.hypotheses.front().score;
            pair.global_status = GlobalRegistrationStatus::kNoConsensus;
        }
        pairs.push_back(pair);
        matchings.push_back(std::move(matching));
    }
    return matchings;
}

void copy_global_figures(const GlobalRegistrationResult& g, PairOutcome& pair) {
    pair.global_status = g.status;
    pair.verified = g.status == GlobalRegistrationStatus::kSuccess;
    pair.weight = pair.verified ? pair_weight(g) : 0.0;
    pair.T_target_source = g.T_target_source;
    pair.global_rms_m = g.rms_m;
    pair.global_overlap_fraction = g.overlap_fraction;
    pair.global_time_s = g.timing.total_s;
}

/// Refines and verifies the matched pairs, best consensus score first, until their scans
/// are connected through verified pairs; pairs of connected scans are skipped.
void verify_pairs(detail::PreparedScans& scans, std::vector<FeatureMatchingResult> matchings,
                  const ScanRegistrationConfig& config, std::vector<PairOutcome>& pairs,
                  const RegistrationProgress& progress) {
    std::vector<std::size_t> order;
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        if (pairs[p].hypotheses > 0) order.push_back(p);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return pairs[a].match_score > pairs[b].match_score;
    });
    detail::DisjointSets connected(scans.size());
    std::vector<std::size_t> failures(scans.size(), 0);
    const std::size_t max_failures = config.max_failed_refinements_per_scan;
    const auto gave_up = [&](std::size_t i) {
        return max_failures > 0 && failures[i] >= max_failures;
    };
    std::size_t tried = 0;
    for (std::size_t p : order) {
        PairOutcome& pair = pairs[p];
        if (connected.find(pair.source) == connected.find(pair.target) || gave_up(pair.source) ||
            gave_up(pair.target)) {
            pair.global_skipped = true;
            continue;
        }
        const std::shared_ptr<const PointCloud> source = scans.cloud(pair.source);
        const std::shared_ptr<const PointCloud> target = scans.cloud(pair.target);
        const ScanFeatures source_f = scans.full_features(pair.source);
        const ScanFeatures target_f = scans.full_features(pair.target);
        const GlobalRegistrationResult g = detail::refine_and_verify(
            {*source, source_f}, {*target, target_f}, std::move(matchings[p]), config.global);
        copy_global_figures(g, pair);
        if (pair.verified) {
            connected.unite(pair.source, pair.target);
        } else {
            ++failures[pair.source];
            ++failures[pair.target];
        }
        report(progress, "global registration " + std::to_string(++tried) + ": scan " +
                             std::to_string(pair.source) + " onto " + std::to_string(pair.target) +
                             " (score " + std::to_string(static_cast<int>(pair.match_score)) +
                             "): " + std::string(to_string(pair.global_status)));
    }
}

/// Why scan i is not in the largest group: what its pairs gave.
std::string not_connected_reason(const ScanRegistrationResult& result, std::size_t i) {
    std::size_t matched = 0, refined = 0, verified = 0;
    for (const PairOutcome& p : result.pairs) {
        if (p.source != i && p.target != i) continue;
        matched += p.hypotheses > 0;
        refined += p.hypotheses > 0 && !p.global_skipped;
        verified += p.verified;
    }
    std::string reason = "no verified chain of pairs to the largest group (in group " +
                         std::to_string(result.scans[i].group) + "): ";
    if (matched == 0) return reason + "no other scan shares consistent features with it";
    return reason + std::to_string(matched) + " pairs with consistent features, " +
           std::to_string(refined) + " refined, " + std::to_string(verified) + " verified";
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
    std::vector<FeatureMatchingResult> matchings =
        match_pairs(prepared.features, detail::candidate_pairs(prepared, config), config.global,
                    result.pairs, progress);
    result.timings.matching_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    verify_pairs(prepared, std::move(matchings), config, result.pairs, progress);
    for (const PairOutcome& p : result.pairs) result.verified_pair_count += p.verified;
    result.timings.pairwise_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    detail::PoseGraph graph = detail::build_pose_graph(usable, result.pairs);
    result.timings.pose_graph_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    const detail::PairLinks links =
        detail::make_links(prepared, graph, result.pairs, config, progress);
    result.link_count = links.links.size();
    result.timings.fine_s = seconds_since(stage);

    stage = std::chrono::steady_clock::now();
    report(progress, "multi-view refinement over " + std::to_string(result.link_count) + " links");
    result.multiview_status = detail::refine_groups(links, config.multiview, graph, result.pairs);
    for (const PairOutcome& p : result.pairs) result.dropped_link_count += p.link_dropped;
    result.timings.multiview_s = seconds_since(stage);

    place_scans(graph, result);
    detail::warn_identical_scans(prepared, result);
    result.cloud_reloads = prepared.store.reload_count();
    result.spill_error = prepared.spill_error;
    result.timings.total_s = seconds_since(start);
    return result;
}

}  // namespace anascan
