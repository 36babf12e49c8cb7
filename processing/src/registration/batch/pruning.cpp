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
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <string>

#include "registration/batch/steps.hpp"

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
    keys.shrink_to_fit();
    return keys;
}

// The inverted index, one bucket of keys at a time: (key, scan) entries partitioned by a
// hash of the key, in memory (one bucket) or in files in the spill directory (one per 32
// scans), so that only one bucket's entries are in memory while votes are counted.
constexpr std::size_t kScansPerBucket = 32;

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

class KeyBuckets {
public:
    KeyBuckets(std::size_t scan_count, const std::filesystem::path& directory) {
        if (directory.empty()) {
            memory_.resize(1);
            return;
        }
        const std::size_t count = (scan_count + kScansPerBucket - 1) / kScansPerBucket;
        std::error_code ignored;
        std::filesystem::create_directories(directory, ignored);
        for (std::size_t b = 0; b < std::max<std::size_t>(count, 1); ++b) {
            paths_.push_back(directory / ("pruning_keys_" + std::to_string(b) + ".bin"));
            files_.emplace_back(std::fopen(paths_.back().c_str(), "w+b"));
            if (!files_.back()) error_ = paths_.back().string() + ": cannot write pruning keys";
        }
    }
    ~KeyBuckets() {
        files_.clear();
        for (const std::filesystem::path& path : paths_) {
            std::error_code ignored;
            std::filesystem::remove(path, ignored);
        }
    }
    KeyBuckets(const KeyBuckets&) = delete;
    KeyBuckets& operator=(const KeyBuckets&) = delete;

    std::size_t count() const { return files_.empty() ? 1 : files_.size(); }
    const std::string& error() const { return error_; }

    void add(std::uint32_t scan, const std::vector<std::uint64_t>& keys) {
        for (std::uint64_t k : keys) {
            const IndexEntry e{.key = k, .scan = scan};
            if (files_.empty()) {
                memory_[0].push_back(e);
                continue;
            }
            std::FILE* f = files_[bucket_of(k)].get();
            if (error_.empty() && (!f || std::fwrite(&e, sizeof e, 1, f) != 1)) {
                error_ = paths_[bucket_of(k)].string() + ": cannot write pruning keys";
            }
        }
    }

    // Bucket b's entries, sorted (the bucket is released).
    std::vector<IndexEntry> take(std::size_t b) {
        std::vector<IndexEntry> entries;
        if (files_.empty()) {
            entries.swap(memory_[0]);
        } else if (std::FILE* f = files_[b].get(); f && std::fseek(f, 0, SEEK_END) == 0) {
            const long bytes = std::ftell(f);
            entries.resize(bytes > 0 ? static_cast<std::size_t>(bytes) / sizeof(IndexEntry) : 0);
            std::rewind(f);
            if (!entries.empty() && std::fread(entries.data(), sizeof(IndexEntry), entries.size(),
                                               f) != entries.size()) {
                if (error_.empty()) error_ = paths_[b].string() + ": cannot read pruning keys";
                entries.clear();
            }
            files_[b].reset();
        }
        tbb::parallel_sort(entries.begin(), entries.end());
        return entries;
    }

private:
    std::size_t bucket_of(std::uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) % files_.size();
    }

    std::vector<std::vector<IndexEntry>> memory_;
    std::vector<std::unique_ptr<std::FILE, FileCloser>> files_;
    std::vector<std::filesystem::path> paths_;
    std::string error_;
};

// Every scan's keys into the buckets (computed in parallel, a block of scans at a time);
// fills the key counts.
void collect_keys(PreparedScans& scans, KeyBuckets& buckets, PairVotes& votes) {
    double diagonal_m = 0.0;
    for (const ScanSummary& s : scans.summary) diagonal_m = std::max(diagonal_m, s.diagonal_m);
    const std::size_t n = scans.size();
    constexpr std::size_t kBlock = 8;  // Scans whose keys are in memory at once.
    for (std::size_t first = 0; first < n; first += kBlock) {
        const std::size_t last = std::min(n, first + kBlock);
        std::vector<FeaturePatchResult> patches;  // Read here: the record file is not shared.
        for (std::size_t i = first; i < last; ++i) {
            patches.push_back(scans.usable(i) ? scans.patches(i) : FeaturePatchResult{});
        }
        std::vector<std::vector<std::uint64_t>> keys(last - first);
        tbb::parallel_for(first, last, [&](std::size_t i) {
            if (scans.usable(i)) keys[i - first] = scan_keys(patches[i - first], 0.25 * diagonal_m);
        });
        for (std::size_t i = first; i < last; ++i) {
            votes.key_count[i] = static_cast<std::uint32_t>(keys[i - first].size());
            buckets.add(static_cast<std::uint32_t>(i), keys[i - first]);
        }
    }
}

}  // namespace

void PairVotes::add_shared_keys(std::span<const IndexEntry> sorted, std::size_t max_holders) {
    const double scans = static_cast<double>(n);
    for (std::size_t lo = 0; lo < sorted.size();) {
        std::size_t hi = lo + 1;
        while (hi < sorted.size() && sorted[hi].key == sorted[lo].key) ++hi;
        const std::size_t holders = hi - lo;
        if (holders >= 2 && holders <= max_holders) {
            const auto weight = static_cast<float>(std::log(scans / static_cast<double>(holders)));
            for (std::size_t a = lo; a < hi; ++a)
                for (std::size_t b = a + 1; b < hi; ++b)
                    at(sorted[a].scan, sorted[b].scan) += weight;
        }
        lo = hi;
    }
}

double PairVotes::similarity(std::size_t i, std::size_t j) const {
    const float v = votes[index(i, j)];
    if (v <= 0.0f) return 0.0;
    return static_cast<double>(v) /
           std::sqrt(static_cast<double>(key_count[i]) * static_cast<double>(key_count[j]));
}

std::vector<std::size_t> PairVotes::most_similar(
    std::size_t i, std::size_t count, const std::function<bool(std::size_t)>& eligible) const {
    std::vector<std::pair<double, std::size_t>> scored;
    for (std::size_t j = 0; j < n; ++j) {
        if (j == i || !eligible(j)) continue;
        if (const double s = similarity(i, j); s > 0.0) scored.emplace_back(-s, j);
    }
    return smallest(std::move(scored), count);
}

CandidatePairs candidate_pairs(PreparedScans& scans, const ScanRegistrationConfig& config) {
    const std::size_t n = scans.size();
    CandidatePairs out;
    if (config.max_candidates_per_scan == 0) {
        for (std::size_t s = 1; s < n; ++s) {
            for (std::size_t t = 0; t < s; ++t) out.pairs.emplace_back(s, t);
        }
        return out;
    }
    PairVotes& votes = out.votes;
    votes.n = n;
    votes.votes.assign(n * (n - 1) / 2, 0.0f);
    votes.key_count.assign(n, 0);
    {
        KeyBuckets buckets(n, scans.spill_directory);
        collect_keys(scans, buckets, votes);
        for (std::size_t b = 0; b < buckets.count(); ++b)
            votes.add_shared_keys(buckets.take(b), kMaxScansPerKey);
        if (!buckets.error().empty()) {
            if (scans.spill_error.empty()) scans.spill_error = buckets.error();
            return out;  // No candidates: every scan is reported not placed.
        }
    }
    std::vector<std::vector<std::size_t>> similar(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        if (votes.key_count[i] > 0)
            similar[i] = votes.most_similar(i, config.max_candidates_per_scan,
                                            [](std::size_t) { return true; });
    });
    std::set<std::pair<std::size_t, std::size_t>> unique;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j : similar[i]) unique.emplace(std::max(i, j), std::min(i, j));
    }
    out.pairs.assign(unique.begin(), unique.end());
    return out;
}

}  // namespace anascan::detail
