#include "anascan/processing/spatial/neighbor_graph.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "anascan/processing/spatial/kdtree.hpp"
#include "core/cpu_features.hpp"
#include "spatial/knn_cells.hpp"
#include "spatial/knn_select.hpp"

namespace anascan {
namespace {

using knn_detail::block_reach_m;
using knn_detail::Candidates;
using knn_detail::CellGrid;
using knn_detail::finite_points;
using knn_detail::gather_block;
using knn_detail::kGroup;
using knn_detail::kMaxRing;
using knn_detail::offer_range;
using knn_detail::pick_range;
using knn_detail::rank_all;
using knn_detail::RowCursors;
using knn_detail::scan_all;
using knn_detail::size_cells;
using knn_detail::sort_into_cells;
using knn_detail::TopK;

// The previous query's squared k-th distance times this bounds the next one's search
// first (a neighbour in the same cell has a similar neighbourhood); any value is exact.
constexpr float kHintGrowth = 1.25f;
// Up to this many times k candidates within the bound are ranked all pairs at once (no
// data-dependent branch); more are inserted one by one.
constexpr std::size_t kMaxRanked = 3;
// Fewer than k candidates within the hint: the bound grows by this much (clamped) and the
// block is picked again, at most kMaxWidenings times before a scan without a bound.
constexpr float kMinWidening = 1.5f, kMaxWidening = 8.0f;
constexpr int kMaxWidenings = 2;

float max_distance_sq(const NeighborGraphConfig& config) {
    return config.max_radius_m > 0.0f ? config.max_radius_m * config.max_radius_m
                                      : std::numeric_limits<float>::infinity();
}

// Whether `top`, found in the (2r+1)^3 block around `cell`, is provably the exact answer
// for sorted point s: its k-th neighbour (or the radius limit) lies within the block.
bool proven(const CellGrid& grid, std::size_t cell, int r, std::size_t s, const TopK& top) {
    const double reach = block_reach_m(grid, cell, r, s);
    const bool full = top.size() == top.capacity();
    const double needed = full ? double(top.worst()) : double(top.max_d2());
    return needed <= reach * reach;
}

bool too_dense(const Candidates& block, std::size_t k) {  // Piles of duplicates: fall back.
    return block.size() > 64 * k + 1024;
}

// Hands a finished row to the visitor, unpacked into the caller's scratch arrays.
void emit_row(const TopK& top, std::size_t row, const NeighborRowVisitor& visit,
              std::vector<std::uint32_t>& indices, std::vector<float>& d2) {
    const std::size_t n = top.size();
    if (indices.size() < n) {  // Grown only.
        indices.resize(n);
        d2.resize(n);
    }
    std::uint32_t* const pi = indices.data();
    float* const pd = d2.data();
    const std::uint64_t* const keys = top.keys();
    for (std::size_t j = 0; j < n; ++j) {
        pd[j] = std::bit_cast<float>(std::uint32_t(keys[j] >> 32));
        pi[j] = std::uint32_t(keys[j]);
    }
    visit(row, {pi, n}, {pd, n});
}

// Parts [begin, end) of a block to scan: at most one per row of a 3x3x3 block.
struct BlockRanges {
    std::array<std::pair<std::uint32_t, std::uint32_t>, 9> at{};
    std::size_t count = 0;
};

// One worker's scratch: the 3x3x3 block of the current cell and, loaded only for rows it
// cannot prove (borders, sparse spots), the 5x5x5 block.
struct Scratch {
    Candidates near, wide;
    std::size_t wide_cell = std::numeric_limits<std::size_t>::max();
    int wide_ring = 0;
    float hint_d2 = std::numeric_limits<float>::infinity();
    std::vector<float> d2;
    BlockRanges ranges;                 // Parts of the block scanned.
    std::vector<std::uint32_t> picked;  // Block positions within the bound.
    std::vector<float> picked_d2;
    std::vector<std::uint32_t> picked_index;
    std::vector<std::int32_t> picked_rank;
    std::vector<std::int32_t> rank_count;    // Entries per rank, for ties.
    std::vector<std::uint32_t> row_indices;  // The row handed to the visitor.
    std::vector<float> row_d2;
    RowCursors cursors;  // Of the 3x3x3 blocks, for cells in increasing order.
};

// The parts of the block that may hold a point within sqrt(bound_d2) of q: with the rows
// recorded (3x3x3 blocks), the neighbouring cells on a side are skipped when the ball
// around q does not cross the centre cell's face on that side.
void reachable_ranges(const CellGrid& grid, std::size_t cell, const Candidates& block,
                      const Eigen::Vector3f& q, float bound_d2, BlockRanges& ranges) {
    if (block.rows.empty() || !(bound_d2 < std::numeric_limits<float>::infinity())) {
        ranges.at[0] = {0, std::uint32_t(block.size())};
        ranges.count = 1;
        return;
    }
    // Slightly wide, so that no point the float distances would accept is skipped.
    const double reach = std::sqrt(double(bound_d2)) * (1.0 + 1e-5) + 1e-9;
    const Eigen::Array3d& lo = grid.cell_lo_m[cell];
    const Eigen::Array3d u = q.cast<double>().array();
    const Eigen::Array3<bool> below = u - reach<lo, above = u + reach> lo + grid.cell_m;
    const std::size_t t0 = below.x() ? 0 : 1, t1 = above.x() ? 3 : 2;
    std::size_t count = 0;
    for (const Candidates::Row& row : block.rows) {  // Appended always, counted when kept.
        const bool y_ok = row.dy == 0 || (row.dy < 0 ? below.y() : above.y());
        const bool z_ok = row.dz == 0 || (row.dz < 0 ? below.z() : above.z());
        ranges.at[count] = {row.at[t0], row.at[t1]};
        count += y_ok & z_ok & (row.at[t0] < row.at[t1]);
    }
    ranges.count = count;
}

// Ranks by distance alone give equal distances the same rank, that of the first of them
// (equal ranks mean equal distances): those entries get consecutive ranks in index order,
// so that the ranks are those of the (distance, index) keys. Ties are few: only their
// entries are compared with the others.
void break_ties_by_index(const std::uint32_t* index, std::size_t n, std::int32_t* rank,
                         std::vector<std::int32_t>& count) {
    count.assign(2 * n, 0);  // Entries per rank, then each entry's tied entries before it.
    std::int32_t* const before = count.data() + n;
    for (std::size_t c = 0; c < n; ++c) ++count[std::size_t(rank[c])];
    for (std::size_t c = 0; c < n; ++c) {
        if (count[std::size_t(rank[c])] < 2) continue;
        for (std::size_t j = 0; j < n; ++j) {
            before[c] += std::int32_t(rank[j] == rank[c] && index[j] < index[c]);
        }
    }
    for (std::size_t c = 0; c < n; ++c) rank[c] += before[c];
}

// Rank of each of the n picked candidates among them (distance, then index), found by
// comparing all pairs (no branch depends on the data): with AVX2 by distance alone, eight
// against eight at a time, ties then broken by index; else rank_all. Ranks below k give
// the sorted top k directly.
void select_ranked(std::size_t n, Scratch& scratch, TopK& top) {
    // Raw pointers: the stores below cannot then be taken to move the vectors' buffers.
    float* const picked_d2 = scratch.picked_d2.data();
    std::uint32_t* const picked_index = scratch.picked_index.data();
    for (std::size_t c = n; c < n + 2 * kGroup; ++c) {  // Padding: ranks last.
        picked_d2[c] = std::numeric_limits<float>::infinity();
        picked_index[c] = std::numeric_limits<std::uint32_t>::max();
    }
    std::int32_t* rank = scratch.picked_rank.data();
    if (!detail::cpu_has_avx2()) {
        rank_all(picked_d2, picked_index, n, rank);
    } else if (knn_detail::rank_distances_avx2(picked_d2, n, rank) != n * (n - 1) / 2) {
        break_ties_by_index(picked_index, n, rank, scratch.rank_count);
    }
    top.place_ranked(picked_d2, picked_index, rank, n);
}

// The squared distances and point indices of the block's points within `bound_d2` of q
// (sorted point s), in scratch.picked_d2 and scratch.picked_index. Returns their count.
std::size_t pick_within(const CellGrid& grid, std::size_t cell, std::size_t s, float bound_d2,
                        Candidates& block, Scratch& scratch) {
    const Eigen::Vector3f q = grid.position(s);
    reachable_ranges(grid, cell, block, q, bound_d2, scratch.ranges);
    const std::size_t self_pos = block.origin + (s - grid.cell_begin[cell]);
    const float self_x = block.x[self_pos];
    block.x[self_pos] = std::numeric_limits<float>::quiet_NaN();  // Never within any bound.
    std::size_t n = 0;
    float* const picked_d2 = scratch.picked_d2.data();
    std::uint32_t* const picked_index = scratch.picked_index.data();
    if (detail::cpu_has_avx2()) {  // Compacted as picked.
        for (std::size_t r = 0; r < scratch.ranges.count; ++r) {
            const auto [begin, end] = scratch.ranges.at[r];
            n = knn_detail::pick_compact_avx2(block, begin, end, q, bound_d2, picked_d2,
                                              picked_index, n);
        }
    } else {  // Positions in the block first, then their distances and indices.
        float* const d2 = scratch.d2.data();
        std::uint32_t* const picks = scratch.picked.data();
        for (std::size_t r = 0; r < scratch.ranges.count; ++r) {
            const auto [begin, end] = scratch.ranges.at[r];
            n = pick_range(block, begin, end, q, bound_d2, d2, picks, n);
        }
        for (std::size_t c = 0; c < n; ++c) {
            picked_d2[c] = d2[picks[c]];
            picked_index[c] = block.indices[picks[c]];
        }
    }
    block.x[self_pos] = self_x;
    return n;
}

// The bound to try next when only `picked` of k lay within the last one: on a surface the
// count grows with the squared radius, so in proportion, with some margin.
float widened(float bound_d2, std::size_t picked, std::size_t k) {
    const float factor = 1.25f * float(k + 1) / float(picked + 1);
    return bound_d2 * std::clamp(factor, kMinWidening, kMaxWidening);
}

// Nearest neighbours of sorted point s among the block's points. `hint_d2` (the previous
// query's k-th distance, grown) bounds the candidates first; when fewer than k lie within
// it, the bound is widened and the block picked again, and after kMaxWidenings the block
// is scanned without a bound, so the answer is the same either way.
void scan_block(const CellGrid& grid, std::size_t cell, std::size_t s, float hint_d2,
                Candidates& block, Scratch& scratch, TopK& top) {
    const std::size_t room = block.size() + knn_detail::kWideGroup + 2 * kGroup;
    if (scratch.d2.size() < room) {  // Grown only: no refill per query.
        for (auto* v : {&scratch.d2, &scratch.picked_d2}) v->resize(room);
        for (auto* v : {&scratch.picked, &scratch.picked_index}) v->resize(room);
        scratch.picked_rank.resize(room);
    }
    const std::size_t k = top.capacity();
    float bound = std::min(hint_d2, top.max_d2());
    for (int widening = 0;; ++widening) {
        const std::size_t picked = pick_within(grid, cell, s, bound, block, scratch);
        const bool enough = picked >= k || bound >= top.max_d2();
        if (enough && picked <= kMaxRanked * k) {
            select_ranked(picked, scratch, top);
            return;
        }
        if (enough) {  // Too many to rank: one by one, within the bound.
            top.clear(bound);
            break;
        }
        if (widening == kMaxWidenings) {
            top.clear(top.max_d2());
            break;
        }
        bound = std::min(widened(bound, picked, k), top.max_d2());
    }
    offer_range(block, 0, block.size(), grid.position(s), grid.sorted.indices[s], scratch.d2, top);
}

// Retries sorted point s on ever wider blocks around its cell; false when none proves it.
bool answer_wide(const CellGrid& grid, std::size_t cell, std::size_t s, Scratch& scratch,
                 TopK& top) {
    for (int ring = 2; ring <= kMaxRing; ++ring) {
        if (scratch.wide_cell != cell || scratch.wide_ring != ring) {
            gather_block(grid, cell, ring, scratch.wide);
            scratch.wide_cell = cell;
            scratch.wide_ring = ring;
        }
        if (too_dense(scratch.wide, top.capacity())) return false;
        // The k found so far lie in the wider block too: their k-th distance bounds it.
        const bool full = top.size() == top.capacity();
        scan_block(grid, cell, s, full ? top.worst() : top.max_d2(), scratch.wide, scratch, top);
        if (proven(grid, cell, ring, s, top)) return true;
    }
    return false;
}

// Answers the points of `cell` from its blocks; rows they cannot prove exact get flagged.
void answer_cell(const CellGrid& grid, std::size_t cell, std::size_t k, float max_d2,
                 Scratch& scratch, const NeighborRowVisitor& visit,
                 std::vector<std::uint8_t>& fallback) {
    gather_block(grid, cell, 1, scratch.near, &scratch.cursors);
    const bool dense = too_dense(scratch.near, k);
    TopK top(k, max_d2);
    float& hint_d2 = scratch.hint_d2;  // Carried over from the previous cell.
    for (std::size_t s = grid.cell_begin[cell]; s < grid.cell_begin[cell + 1]; ++s) {
        const std::uint32_t row = grid.sorted.indices[s];
        if (dense) {
            fallback[row] = 1;
            continue;
        }
        scan_block(grid, cell, s, hint_d2, scratch.near, scratch, top);
        if (top.size() == k) hint_d2 = kHintGrowth * top.worst();
        if (!proven(grid, cell, 1, s, top) && !answer_wide(grid, cell, s, scratch, top)) {
            fallback[row] = 1;
            continue;
        }
        emit_row(top, row, visit, scratch.row_indices, scratch.row_d2);
    }
}

// Exact answers for the flagged rows: linear scans when they are few (building a k-d tree
// costs about as much as kBruteForceRows scans), else k-d tree queries. Returns their count.
std::size_t answer_fallbacks(std::span<const Eigen::Vector3f> points, const Candidates& finite,
                             std::size_t k, float max_d2, const std::vector<std::uint8_t>& flags,
                             const NeighborRowVisitor& visit) {
    constexpr std::size_t kBruteForceRows = 256;
    std::vector<std::uint32_t> rows;
    for (std::size_t i = 0; i < flags.size(); ++i) {
        if (flags[i]) rows.push_back(std::uint32_t(i));
    }
    if (rows.empty()) return 0;
    if (rows.size() <= kBruteForceRows) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 8), [&](auto r) {
            TopK top(k, max_d2);
            std::vector<float> d2, row_d2;
            std::vector<std::uint32_t> row_indices;
            for (std::size_t j = r.begin(); j < r.end(); ++j) {
                scan_all(finite, points[rows[j]], rows[j], d2, top);
                emit_row(top, rows[j], visit, row_indices, row_d2);
            }
        });
        return rows.size();
    }
    std::vector<Eigen::Vector3f> positions(finite.size());
    for (std::size_t s = 0; s < finite.size(); ++s) {
        positions[s] = {finite.x[s], finite.y[s], finite.z[s]};
    }
    const KdTree tree(positions);  // Finite points only; map back through finite.indices.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 64), [&](const auto& r) {
        std::vector<Neighbor> found;
        TopK top(k, max_d2);
        std::vector<float> row_d2;
        std::vector<std::uint32_t> row_indices;
        for (std::size_t j = r.begin(); j < r.end(); ++j) {
            const std::uint32_t row = rows[j];
            tree.knn(points[row], k + 1, found);
            top.clear(max_d2);
            for (const Neighbor& n : found) {
                const std::uint32_t index = finite.indices[n.index];
                if (index != row) top.offer(n.distance_sq_m2, index);
            }
            emit_row(top, row, visit, row_indices, row_d2);
        }
    });
    return rows.size();
}

}  // namespace

std::size_t visit_neighbor_rows(std::span<const Eigen::Vector3f> points,
                                const NeighborGraphConfig& config,
                                const NeighborRowVisitor& visit) {
    assert(points.size() < std::numeric_limits<std::uint32_t>::max());
    const auto k = std::size_t(std::max(config.k_neighbors, 1));
    const Candidates finite = finite_points(points);
    if (finite.size() == 0) return 0;
    CellGrid grid;
    size_cells(finite, config, k, grid);
    sort_into_cells(finite, grid);
    const float max_d2 = max_distance_sq(config);
    std::vector<std::uint8_t> fallback(points.size(), 0);
    const std::size_t num_cells = grid.cell_keys.size();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_cells, 16), [&](const auto& r) {
        Scratch scratch;
        for (std::size_t cell = r.begin(); cell < r.end(); ++cell) {
            answer_cell(grid, cell, k, max_d2, scratch, visit, fallback);
        }
    });
    return answer_fallbacks(points, finite, k, max_d2, fallback, visit);
}

NeighborGraph build_neighbor_graph(std::span<const Eigen::Vector3f> points,
                                   const NeighborGraphConfig& config) {
    NeighborGraph graph;
    graph.k = std::size_t(std::max(config.k_neighbors, 1));
    graph.indices.assign(points.size() * graph.k, 0);
    graph.distances_sq_m2.assign(points.size() * graph.k, 0.0f);
    graph.counts.assign(points.size(), 0);
    graph.num_exact_fallbacks = visit_neighbor_rows(
        points, config,
        [&](std::size_t i, std::span<const std::uint32_t> neighbors, std::span<const float> d2) {
            std::copy(neighbors.begin(), neighbors.end(),
                      graph.indices.begin() + std::ptrdiff_t(i * graph.k));
            std::copy(d2.begin(), d2.end(),
                      graph.distances_sq_m2.begin() + std::ptrdiff_t(i * graph.k));
            graph.counts[i] = std::uint32_t(neighbors.size());
        });
    return graph;
}

}  // namespace anascan
