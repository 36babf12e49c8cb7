// Pair pruning for register_scans: for each scan, the scans sharing the most feature
// triangles become its only matching candidates (instead of all N(N-1)/2 pairs).
//
// A feature triangle joins a patch and two of its nearest patches; its key is the three
// side lengths (quantised) with the kind (radius, side) of the opposite corners, in a
// canonical order, so it does not depend on the pose. Two overlapping scans share the
// triangles of their common part; unrelated scans share only what chance gives (three
// quantised lengths and three kinds rarely coincide). Keys go into an inverted index and
// every pair of scans sharing a key gets a vote (keys held by very many scans are skipped
// as uninformative). The score of a pair is votes / sqrt(keys_a keys_b).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "scan_registration_steps.hpp"

namespace anascan::detail {
namespace {

constexpr std::size_t kNearestPatches = 8;   // Triangle partners of each patch.
constexpr double kLengthBins = 32.0;         // Quantisation: longest side / this.
constexpr double kMinSideBins = 2.0;         // Shorter sides: one bump twice.
constexpr std::size_t kMaxScansPerKey = 64;  // More: too common to tell scans apart.

std::uint64_t patch_kind(const FeaturePatch& p) {
    return 2 * p.radius_index + static_cast<std::uint64_t>(p.side);
}

// The keys of the triangle (a, b, c): per side its length bin and, for robustness to the
// jitter of barycentres, the nearer neighbouring bin (2^3 combinations); each key is the
// (side bin, kind of the opposite corner) triples in sorted order.
void triangle_keys(const std::vector<FeaturePatch>& p, std::size_t a, std::size_t b, std::size_t c,
                   double bin_m, std::vector<std::uint64_t>& keys) {
    const std::array<std::size_t, 3> corner{a, b, c};
    std::array<std::array<std::uint64_t, 2>, 3> bins{};
    for (std::size_t k = 0; k < 3; ++k) {
        const FeaturePatch& u = p[corner[(k + 1) % 3]];
        const FeaturePatch& v = p[corner[(k + 2) % 3]];
        const double x = (u.barycentre_m - v.barycentre_m).norm() / bin_m;
        const auto bin = static_cast<std::uint64_t>(x);
        const bool upper = x - static_cast<double>(bin) >= 0.5;
        bins[k] = {bin, upper ? bin + 1 : (bin > 0 ? bin - 1 : bin)};
    }
    for (unsigned combo = 0; combo < 8; ++combo) {
        std::array<std::uint64_t, 3> t{};
        for (std::size_t k = 0; k < 3; ++k) {
            t[k] = bins[k][(combo >> k) & 1u] << 4 | patch_kind(p[corner[k]]);
        }
        std::sort(t.begin(), t.end());
        keys.push_back(t[0] << 42 | t[1] << 21 | t[2]);
    }
}

// The distinct triangle keys of one scan (sorted). Sides longer than `max_side_m` are not
// used. Patches of the middle saliency level only: the levels nest (a peak gives one
// patch per level), so one level gives each bump once.
std::vector<std::uint64_t> scan_keys(const FeaturePatchResult& patches, double max_side_m) {
    std::vector<FeaturePatch> p;
    for (const FeaturePatch& patch : patches.patches) {
        if (patch.level == kSaliencyLevels / 2) p.push_back(patch);
    }
    const double bin_m = max_side_m / kLengthBins;
    std::vector<std::uint64_t> keys;
    std::vector<std::pair<double, std::size_t>> near;
    for (std::size_t a = 0; a < p.size(); ++a) {
        near.clear();
        for (std::size_t b = 0; b < p.size(); ++b) {  // Same radius, not the same bump.
            const double d = (p[a].barycentre_m - p[b].barycentre_m).norm();
            if (b != a && p[b].radius_index == p[a].radius_index && d < max_side_m &&
                d >= kMinSideBins * bin_m) {
                near.emplace_back(d, b);
            }
        }
        const std::size_t keep = std::min(kNearestPatches, near.size());
        std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(keep),
                          near.end());
        for (std::size_t i = 0; i < keep; ++i) {
            for (std::size_t j = i + 1; j < keep; ++j) {
                const std::size_t b = near[i].second, c = near[j].second;
                const double bc = (p[b].barycentre_m - p[c].barycentre_m).norm();
                if (bc >= max_side_m || bc < kMinSideBins * bin_m) continue;
                triangle_keys(p, a, b, c, bin_m, keys);
            }
        }
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    return keys;
}

// The inverted index as one sorted array of (key, scan): 16 bytes per key of every scan,
// no per-key allocation (a hash map of vectors cost several times more at 1000 scans).
using IndexEntry = std::pair<std::uint64_t, std::uint32_t>;

std::vector<IndexEntry> inverted_index(const std::vector<std::vector<std::uint64_t>>& keys) {
    std::size_t total = 0;
    for (const auto& k : keys) total += k.size();
    std::vector<IndexEntry> index;
    index.reserve(total);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        for (std::uint64_t k : keys[i]) index.emplace_back(k, static_cast<std::uint32_t>(i));
    }
    tbb::parallel_sort(index.begin(), index.end());
    return index;
}

// Scan i's `count` best partners by idf-weighted shared keys / sqrt(keys_i keys_j) (ties by
// index); `votes` is scratch of size N, left zero.
std::vector<std::size_t> best_partners(const std::vector<std::vector<std::uint64_t>>& keys,
                                       const std::vector<IndexEntry>& index, std::size_t i,
                                       std::size_t count, std::vector<double>& votes) {
    const double n = static_cast<double>(keys.size());
    std::vector<std::uint32_t> touched;
    for (std::uint64_t k : keys[i]) {
        const auto lo = std::lower_bound(index.begin(), index.end(), IndexEntry{k, 0});
        auto hi = lo;
        while (hi != index.end() && hi->first == k) ++hi;
        const auto holders = static_cast<std::size_t>(hi - lo);
        if (holders < 2 || holders > kMaxScansPerKey) continue;
        const double weight = std::log(n / static_cast<double>(holders));  // Rare: more.
        for (auto it = lo; it != hi; ++it) {
            if (it->second == i) continue;
            if (votes[it->second] == 0.0) touched.push_back(it->second);
            votes[it->second] += weight;
        }
    }
    std::vector<std::pair<double, std::size_t>> scored;
    for (std::uint32_t j : touched) {
        const double norm = std::sqrt(static_cast<double>(keys[i].size() * keys[j].size()));
        scored.emplace_back(-votes[j] / norm, j);
        votes[j] = 0.0;
    }
    const std::size_t keep = std::min(count, scored.size());
    std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(keep),
                      scored.end());
    std::vector<std::size_t> out;
    for (std::size_t r = 0; r < keep; ++r) out.push_back(scored[r].second);
    return out;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> candidate_pairs(
    const PreparedScans& scans, const ScanRegistrationConfig& config) {
    const std::size_t n = scans.size();
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    if (config.max_candidates_per_scan == 0) {
        for (std::size_t s = 1; s < n; ++s) {
            for (std::size_t t = 0; t < s; ++t) pairs.emplace_back(s, t);
        }
        return pairs;
    }
    double diagonal_m = 0.0;
    for (const ScanSummary& s : scans.summary) diagonal_m = std::max(diagonal_m, s.diagonal_m);
    std::vector<std::vector<std::uint64_t>> keys(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        if (scans.usable(i)) keys[i] = scan_keys(scans.features[i].patches, 0.25 * diagonal_m);
    });
    const std::vector<IndexEntry> index = inverted_index(keys);
    std::vector<std::vector<std::size_t>> similar(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16), [&](const auto& r) {
        std::vector<double> votes(n, 0.0);
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            if (!keys[i].empty()) {
                similar[i] = best_partners(keys, index, i, config.max_candidates_per_scan, votes);
            }
        }
    });
    std::set<std::pair<std::size_t, std::size_t>> unique;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j : similar[i]) unique.emplace(std::max(i, j), std::min(i, j));
    }
    return {unique.begin(), unique.end()};
}

}  // namespace anascan::detail
