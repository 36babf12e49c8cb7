// The campaign's candidate pairs: an inverted index over the scans' descriptor keys; every
// two scans holding a key get its idf weight as a vote, and each scan proposes the scans it
// shares the most votes with (normalised by the key counts).
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "anascan/processing/campaign/campaign_stages.hpp"
#include "registration/batch/steps.hpp"

namespace anascan {
namespace {

using detail::IndexEntry;

std::vector<IndexEntry> index_entries(const std::vector<std::vector<std::uint64_t>>& keys) {
    std::vector<IndexEntry> entries;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        for (std::uint64_t k : keys[i]) entries.push_back({k, static_cast<std::uint32_t>(i)});
    }
    tbb::parallel_sort(entries.begin(), entries.end());
    return entries;
}

}  // namespace

std::vector<CandidatePair> propose_candidates(const std::vector<std::vector<std::uint64_t>>& keys,
                                              const CampaignConfig& config) {
    const std::size_t n = keys.size();
    if (n < 2) return {};
    detail::PairVotes votes;
    votes.n = n;
    votes.votes.assign(n * (n - 1) / 2, 0.0f);
    votes.key_count.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        votes.key_count[i] = static_cast<std::uint32_t>(keys[i].size());
    }
    votes.add_shared_keys(index_entries(keys), config.max_scans_per_key);
    std::vector<std::vector<std::size_t>> similar(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        if (votes.key_count[i] > 0)
            similar[i] =
                votes.most_similar(i, config.candidates_per_scan, [](std::size_t) { return true; });
    });
    std::set<std::pair<std::size_t, std::size_t>> unique;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j : similar[i]) unique.emplace(std::max(i, j), std::min(i, j));
    }
    std::vector<CandidatePair> out;
    for (const auto& [s, t] : unique) out.push_back({s, t, votes.similarity(s, t)});
    return out;
}

}  // namespace anascan
