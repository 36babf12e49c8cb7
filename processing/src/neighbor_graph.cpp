#include "anascan/processing/neighbor_graph.hpp"

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

#include "anascan/processing/kdtree.hpp"
#include "neighbor_graph_select.hpp"

namespace anascan {
namespace {

using knn_detail::Candidates;
using knn_detail::kGroup;
using knn_detail::offer_range;
using knn_detail::pick_range;
using knn_detail::rank_all;
using knn_detail::scan_all;
using knn_detail::TopK;

// Cell side over the (median, sampled) distance to the k-th neighbour: ~10 points per
// cell on the bunny scans, and the 3x3x3 block around a query proves almost every row.
constexpr double kCellPerRadius = 2.0;
constexpr std::size_t kRadiusSamples = 8;  // Queries answered by brute force to size cells.
// The previous query's squared k-th distance times this bounds the next one's search
// first (a neighbour in the same cell has a similar neighbourhood); any value is exact.
constexpr float kHintGrowth = 1.25f;
// Rows the 3x3x3 block cannot prove are retried on the 5x5x5 block, and so on up to
// (2 kMaxRing + 1)^3; the few left (outliers) are answered by linear scans or a k-d tree.
constexpr int kMaxRing = 4;
// Up to this many times k candidates within the bound are ranked all pairs at once (no
// data-dependent branch); more are inserted one by one.
constexpr std::size_t kMaxRanked = 3;
// Fewer than k candidates within the hint: the bound grows by this much (clamped) and the
// block is picked again, at most kMaxWidenings times before a scan without a bound.
constexpr float kMinWidening = 1.5f, kMaxWidening = 8.0f;
constexpr int kMaxWidenings = 2;
// Open addressing from a key to a number (keys < 2^63; the empty slot is ~0).
class CellTable {
public:
    // Unique keys, each with its number.
    void build(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& entries) {
        const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * entries.size(), 16));
        shift_ = 64 - std::countr_zero(capacity);
        mask_ = capacity - 1;
        slots_.assign(capacity, {kEmpty, 0});
        for (const auto& entry : entries) {
            std::size_t h = hash(entry.first);
            while (slots_[h].first != kEmpty) h = (h + 1) & mask_;
            slots_[h] = entry;
        }
    }
    // The number of `key`, or -1.
    std::ptrdiff_t find(std::uint64_t key) const {
        for (std::size_t h = hash(key);; h = (h + 1) & mask_) {
            if (slots_[h].first == key) return slots_[h].second;
            if (slots_[h].first == kEmpty) return -1;
        }
    }

private:
    static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
    std::size_t hash(std::uint64_t key) const {
        return std::size_t((key * 0x9E3779B97F4A7C15ULL) >> shift_);
    }
    int shift_ = 60;
    std::size_t mask_ = 0;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> slots_;
};

// Finite points sorted by cell, cells numbered row by row (x fastest), so the cells
// x - r .. x + r of a row hold one contiguous run of points.
struct CellGrid {
    Eigen::Vector3d min_m = Eigen::Vector3d::Zero();
    double cell_m = 1.0;
    Eigen::Array3<std::int64_t> dims = Eigen::Array3<std::int64_t>::Ones();
    Candidates sorted;                      // Finite points in cell order, original indices.
    std::vector<std::uint64_t> cell_keys;   // Sorted, unique.
    std::vector<std::uint32_t> cell_begin;  // cell_keys.size() + 1 offsets into `sorted`.
    std::vector<Eigen::Array3d> cell_lo_m;  // Lower corner of each cell (no division per query).
    CellTable row_table;  // Row key (z * dims.y + y) to the first cell of that row.

    std::uint64_t key(const Eigen::Array3<std::int64_t>& c) const {
        return std::uint64_t((c.z() * dims.y() + c.y()) * dims.x() + c.x());
    }
    Eigen::Array3<std::int64_t> coords(std::uint64_t key) const {
        const auto k = std::int64_t(key);
        return {k % dims.x(), k / dims.x() % dims.y(), k / (dims.x() * dims.y())};
    }
    Eigen::Array3<std::int64_t> cell_of(float x, float y, float z) const {
        const Eigen::Array3d u = (Eigen::Vector3d(x, y, z) - min_m).array() / cell_m;
        return u.floor().cast<std::int64_t>().max(0).min(dims - 1);
    }
    Eigen::Vector3f position(std::size_t s) const {
        return {sorted.x[s], sorted.y[s], sorted.z[s]};
    }
};

// Finite points as arrays, in index order.
// Copied in parallel; the rare cloud with non-finite points is then compacted in order.
Candidates finite_points(std::span<const Eigen::Vector3f> points) {
    const std::size_t n = points.size();
    Candidates out;
    out.x.resize(n);
    out.y.resize(n);
    out.z.resize(n);
    out.indices.resize(n);
    const std::size_t finite = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 8192), std::size_t(0),
        [&](const auto& r, std::size_t count) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                out.x[i] = points[i].x();
                out.y[i] = points[i].y();
                out.z[i] = points[i].z();
                out.indices[i] = std::uint32_t(i);
                count += points[i].allFinite();
            }
            return count;
        },
        std::plus<>());
    if (finite == n) return out;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!points[i].allFinite()) continue;
        out.x[kept] = out.x[i];
        out.y[kept] = out.y[i];
        out.z[kept] = out.z[i];
        out.indices[kept++] = out.indices[i];
    }
    for (knn_detail::Array<float>* v : {&out.x, &out.y, &out.z}) v->resize(kept);
    out.indices.resize(kept);
    return out;
}

// Median distance to the k-th neighbour over evenly spaced sample points (exact, by linear
// scans); infinite when the cloud has k points or fewer.
double sampled_knn_radius(const Candidates& finite, std::size_t k) {
    const std::size_t n = finite.size(), m = std::min(kRadiusSamples, n);
    std::vector<double> radii(m);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 1), [&](auto r) {
        std::vector<float> d2;
        TopK top(k, std::numeric_limits<float>::infinity());
        for (std::size_t j = r.begin(); j < r.end(); ++j) {
            const std::size_t s = j * n / m;
            const Eigen::Vector3f q(finite.x[s], finite.y[s], finite.z[s]);
            scan_all(finite, q, finite.indices[s], d2, top);
            radii[j] = top.size() == k ? std::sqrt(double(top.worst()))
                                       : std::numeric_limits<double>::infinity();
        }
    });
    std::nth_element(radii.begin(), radii.begin() + std::ptrdiff_t(m / 2), radii.end());
    return radii[m / 2];
}

// Cell side from the sampled k-th neighbour distance (or the radius limit, when smaller),
// at least 2^-20 of the extent so that cell keys fit in 63 bits.
void size_cells(const Candidates& finite, const NeighborGraphConfig& config, std::size_t k,
                CellGrid& grid) {
    using Box = std::pair<Eigen::Vector3d, Eigen::Vector3d>;
    const Box empty{Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY)};
    const auto [lo, hi] = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, finite.size(), 8192), empty,
        [&](const auto& r, Box box) {
            for (std::size_t s = r.begin(); s < r.end(); ++s) {
                const Eigen::Vector3d p(finite.x[s], finite.y[s], finite.z[s]);
                box.first = box.first.cwiseMin(p);
                box.second = box.second.cwiseMax(p);
            }
            return box;
        },
        [](const Box& a, const Box& b) {
            return Box{a.first.cwiseMin(b.first), a.second.cwiseMax(b.second)};
        });
    const double extent = (hi - lo).maxCoeff();
    double cell = kCellPerRadius * sampled_knn_radius(finite, k);
    if (config.max_radius_m > 0.0f) cell = std::min(cell, double(config.max_radius_m));
    cell = std::min(cell, extent);  // Infinite when the cloud is tiny: one cell.
    cell = std::max(cell, std::max(extent, 1e-9) / double(1 << 20));
    grid.min_m = lo;
    grid.cell_m = cell;
    grid.dims = ((hi - lo) / cell).array().floor().cast<std::int64_t>() + 1;
}

// Stable LSD radix sort on the key, a byte a pass (the buckets stay in L1), as many passes
// as the largest key needs (three for ~10^5 cells): linear passes, no comparison sort.
void sort_by_key(std::vector<std::pair<std::uint64_t, std::uint32_t>>& keyed) {
    constexpr int kDigitBits = 8;
    constexpr std::size_t kBuckets = std::size_t(1) << kDigitBits;
    std::uint64_t largest = 0;
    for (const auto& entry : keyed) largest = std::max(largest, entry.first);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> other(keyed.size());
    std::vector<std::size_t> start(kBuckets);
    for (int shift = 0; shift < int(std::bit_width(largest)); shift += kDigitBits) {
        std::fill(start.begin(), start.end(), 0);
        for (const auto& entry : keyed) ++start[(entry.first >> shift) & (kBuckets - 1)];
        std::size_t offset = 0;
        for (std::size_t& s : start) offset += std::exchange(s, offset);
        for (const auto& entry : keyed)
            other[start[(entry.first >> shift) & (kBuckets - 1)]++] = entry;
        keyed.swap(other);
    }
}

// Sorts the finite points by cell (ties by index: deterministic) and numbers the cells.
void sort_into_cells(const Candidates& finite, CellGrid& grid) {
    const std::size_t n = finite.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](auto r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s) {
            keyed[s] = {grid.key(grid.cell_of(finite.x[s], finite.y[s], finite.z[s])),
                        std::uint32_t(s)};
        }
    });
    sort_by_key(keyed);
    Candidates& out = grid.sorted;
    out.x.resize(n);
    out.y.resize(n);
    out.z.resize(n);
    out.indices.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](auto r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s) {
            const std::uint32_t from = keyed[s].second;
            out.x[s] = finite.x[from];
            out.y[s] = finite.y[from];
            out.z[s] = finite.z[from];
            out.indices[s] = finite.indices[from];
        }
    });
    for (std::size_t s = 0; s < n; ++s) {
        if (s == 0 || keyed[s].first != keyed[s - 1].first) {
            grid.cell_keys.push_back(keyed[s].first);
            grid.cell_begin.push_back(std::uint32_t(s));
        }
    }
    grid.cell_begin.push_back(std::uint32_t(n));
    std::vector<std::pair<std::uint64_t, std::uint32_t>> rows;  // Row key, first cell.
    for (std::size_t c = 0; c < grid.cell_keys.size(); ++c) {
        const std::uint64_t row = grid.cell_keys[c] / std::uint64_t(grid.dims.x());
        if (rows.empty() || rows.back().first != row) rows.emplace_back(row, std::uint32_t(c));
    }
    grid.row_table.build(rows);
    grid.cell_lo_m.resize(grid.cell_keys.size());
    for (std::size_t c = 0; c < grid.cell_keys.size(); ++c) {
        grid.cell_lo_m[c] =
            grid.min_m.array() + grid.coords(grid.cell_keys[c]).cast<double>() * grid.cell_m;
    }
}

// Row offsets (dy, dz) of a (2r+1)^3 block, nearest first, so that the k-th distance
// tightens early and most later candidates are rejected four at a time.
std::vector<Eigen::Array2<std::int64_t>> row_offsets(int r) {
    std::vector<Eigen::Array2<std::int64_t>> offsets;
    for (int dz = -r; dz <= r; ++dz) {
        for (int dy = -r; dy <= r; ++dy) offsets.emplace_back(dy, dz);
    }
    std::stable_sort(offsets.begin(), offsets.end(), [](const auto& a, const auto& b) {
        return a.square().sum() < b.square().sum();
    });
    return offsets;
}

// The points of the (2r+1)^3 block of cells around `cell`, one contiguous run per row,
// nearest rows first.
// Where each row of the 3x3x3 block stood in the sorted cells for the previous cell: a
// worker answers cells in increasing order, and the first key of each row (when the row
// lies in the grid) then only grows, so rows are found by stepping forward from there
// instead of by hash look-ups.
struct RowCursors {
    std::array<std::size_t, 9> at{};
    std::array<bool, 9> started{};
};

// The first cell with a key in [lo, hi] (a run of one row), or -1, searched from the
// row's first cell (-1: the row is empty).
std::ptrdiff_t first_in_row(const CellGrid& grid, std::uint64_t lo, std::uint64_t hi,
                            std::ptrdiff_t row_start) {
    if (row_start < 0) return -1;
    const std::vector<std::uint64_t>& keys = grid.cell_keys;
    const auto at = std::lower_bound(keys.begin() + row_start, keys.end(), lo);
    return at != keys.end() && *at <= hi ? at - keys.begin() : -1;
}

// The first cell with a key in [lo, hi] (a run of one row), or -1; row o of the block.
std::ptrdiff_t first_in_row(const CellGrid& grid, std::uint64_t lo, std::uint64_t hi,
                            RowCursors& cursors, std::size_t o) {
    const std::vector<std::uint64_t>& keys = grid.cell_keys;
    std::size_t& at = cursors.at[o];
    if (!cursors.started[o]) {
        at = std::size_t(std::lower_bound(keys.begin(), keys.end(), lo) - keys.begin());
        cursors.started[o] = true;
    }
    while (at < keys.size() && keys[at] < lo) ++at;
    return at < keys.size() && keys[at] <= hi ? std::ptrdiff_t(at) : -1;
}

void gather_block(const CellGrid& grid, std::size_t cell, int r, Candidates& block,
                  RowCursors* cursors = nullptr) {
    static const std::array<std::vector<Eigen::Array2<std::int64_t>>, kMaxRing + 1> kRows = [] {
        std::array<std::vector<Eigen::Array2<std::int64_t>>, kMaxRing + 1> rows;
        for (int ring = 1; ring <= kMaxRing; ++ring) rows[std::size_t(ring)] = row_offsets(ring);
        return rows;
    }();
    block.clear();
    const Eigen::Array3<std::int64_t> c = grid.coords(grid.cell_keys[cell]);
    const std::int64_t x0 = std::max<std::int64_t>(c.x() - r, 0);
    const std::int64_t x1 = std::min<std::int64_t>(c.x() + r, grid.dims.x() - 1);
    const std::vector<Eigen::Array2<std::int64_t>>& offsets = kRows[std::size_t(r)];
    std::uint32_t size = 0;  // Of the block so far: the runs are copied at the end, at once.
    for (std::size_t o = 0; o < offsets.size(); ++o) {
        const Eigen::Array2<std::int64_t>& offset = offsets[o];
        const std::int64_t y = c.y() + offset.x(), z = c.z() + offset.y();
        if (y < 0 || z < 0 || y >= grid.dims.y() || z >= grid.dims.z()) continue;
        const std::uint64_t last_key = grid.key({x1, y, z});
        std::ptrdiff_t first = -1;
        if (cursors) {
            first = first_in_row(grid, grid.key({x0, y, z}), last_key, *cursors, o);
        } else {
            first = first_in_row(grid, grid.key({x0, y, z}), last_key,
                                 grid.row_table.find(std::uint64_t(z * grid.dims.y() + y)));
        }
        if (first < 0) continue;
        auto last = std::size_t(first);
        while (last + 1 < grid.cell_keys.size() && grid.cell_keys[last + 1] <= last_key) ++last;
        const std::uint32_t base = grid.cell_begin[std::size_t(first)];
        if (offset.isZero()) block.origin = size + grid.cell_begin[cell] - base;
        if (r == 1) {
            Candidates::Row row{offset.x(), offset.y(), {}};
            auto at = std::size_t(first);
            for (std::size_t t = 1; t < 3; ++t) {  // First cell at x - 1 + t or beyond.
                const std::uint64_t from = grid.key({c.x() - 1 + std::int64_t(t), y, z});
                while (at <= last && grid.cell_keys[at] < from) ++at;
                row.at[t] = size + grid.cell_begin[at] - base;
            }
            row.at[0] = size;
            row.at[3] = size + grid.cell_begin[last + 1] - base;
            block.rows.push_back(row);
        }
        block.runs.emplace_back(base, grid.cell_begin[last + 1]);
        size += grid.cell_begin[last + 1] - base;
    }
    block.copy_runs(grid.sorted, size);
}

// Distance (metres) from sorted point s to the outside of the (2r+1)^3 block of cells
// around its cell: every point closer than that lies in the block.
double block_reach_m(const CellGrid& grid, std::size_t cell, int r, std::size_t s) {
    const Eigen::Array3d& lo = grid.cell_lo_m[cell];
    const Eigen::Array3d u = grid.position(s).cast<double>().array();
    const double margin = std::max(((u - lo).min(lo + grid.cell_m - u)).minCoeff(), 0.0);
    return (double(r) * grid.cell_m + margin) * (1.0 - 1e-6);
}

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
    if (!knn_detail::have_avx2()) {
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
    if (knn_detail::have_avx2()) {  // Compacted as picked.
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
