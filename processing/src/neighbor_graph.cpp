#include "anascan/processing/neighbor_graph.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "anascan/processing/kdtree.hpp"

namespace anascan {
namespace {

constexpr int kMortonBits = 21;  // Per axis: 63-bit keys.
constexpr double kMaxCoord = double((1u << kMortonBits) - 1);
// The previous query's squared k-th distance times this bounds the next one's search
// first (a neighbour in Morton order has a similar neighbourhood); any value is exact.
constexpr float kHintGrowth = 1.5f;

std::uint64_t spread_bits(std::uint64_t v) {  // 21 bits -> every third bit.
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

std::uint64_t compact_bits(std::uint64_t v) {  // Inverse of spread_bits.
    v &= 0x1249249249249249ULL;
    v = (v ^ (v >> 2)) & 0x10c30c30c30c30c3ULL;
    v = (v ^ (v >> 4)) & 0x100f00f00f00f00fULL;
    v = (v ^ (v >> 8)) & 0x1f0000ff0000ffULL;
    v = (v ^ (v >> 16)) & 0x1f00000000ffffULL;
    v = (v ^ (v >> 32)) & 0x1fffff;
    return v;
}

std::uint64_t morton(const Eigen::Array3<std::int64_t>& c) {
    return spread_bits(std::uint64_t(c.x())) | spread_bits(std::uint64_t(c.y())) << 1 |
           spread_bits(std::uint64_t(c.z())) << 2;
}

Eigen::Array3<std::int64_t> demorton(std::uint64_t key) {
    return {std::int64_t(compact_bits(key)), std::int64_t(compact_bits(key >> 1)),
            std::int64_t(compact_bits(key >> 2))};
}

bool is_finite(const Eigen::Vector3f& p) { return p.allFinite(); }

// Finite points quantised to a 2^21 lattice over their bounds and sorted along the Morton
// curve; cells of side 2^level lattice units are runs of equal key >> (3 * level).
struct MortonGrid {
    Eigen::Vector3d min_m = Eigen::Vector3d::Zero();
    double units_per_m = 1.0;
    int level = 0;
    std::vector<std::uint64_t> keys;      // Sorted point keys.
    std::vector<std::uint32_t> order;     // Point index of each sorted key.
    std::vector<Eigen::Vector3f> sorted;  // Positions in sorted order.
    std::vector<float> sx, sy, sz;        // The same as arrays (vectorised linear scans).
    std::vector<std::uint64_t> cell_keys;
    std::vector<std::uint32_t> cell_begin;  // cell_keys.size() + 1 offsets into `sorted`.

    Eigen::Vector3d lattice(const Eigen::Vector3f& p) const {
        return ((p.cast<double>() - min_m) * units_per_m).cwiseMax(0.0).cwiseMin(kMaxCoord);
    }
    // Index of the cell with these cell coordinates, or -1.
    std::ptrdiff_t find_cell(const Eigen::Array3<std::int64_t>& c) const {
        const std::int64_t max_c = std::int64_t(kMaxCoord) >> level;
        if ((c < 0).any() || (c > max_c).any()) return -1;
        const std::uint64_t key = morton(c);
        const auto it = std::lower_bound(cell_keys.begin(), cell_keys.end(), key);
        return it != cell_keys.end() && *it == key ? it - cell_keys.begin() : -1;
    }
};

void sort_points(std::span<const Eigen::Vector3f> points, MortonGrid& grid) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector3f& p : points) {
        if (!is_finite(p)) continue;
        lo = lo.cwiseMin(p.cast<double>());
        hi = hi.cwiseMax(p.cast<double>());
    }
    if (!(lo.x() <= hi.x())) return;  // No finite point.
    grid.min_m = lo;
    grid.units_per_m = kMaxCoord / std::max((hi - lo).maxCoeff(), 1e-9);
    // Keys in parallel (non-finite points get the largest key and are cut off after the
    // sort: a finite key never reaches it, 63 bits are used).
    constexpr std::uint64_t kNoKey = std::numeric_limits<std::uint64_t>::max();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 4096), [&](auto r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const std::uint64_t key =
                is_finite(points[i])
                    ? morton(grid.lattice(points[i]).array().floor().cast<std::int64_t>())
                    : kNoKey;
            keyed[i] = {key, std::uint32_t(i)};
        }
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());  // Unique pairs: deterministic order.
    std::size_t finite = keyed.size();
    while (finite > 0 && keyed[finite - 1].first == kNoKey) --finite;
    grid.keys.resize(finite);
    grid.order.resize(finite);
    grid.sorted.resize(finite);
    for (auto* axis : {&grid.sx, &grid.sy, &grid.sz}) axis->resize(finite);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, finite, 4096), [&](auto r) {
        for (std::size_t s = r.begin(); s < r.end(); ++s) {
            grid.keys[s] = keyed[s].first;
            grid.order[s] = keyed[s].second;
            grid.sorted[s] = points[keyed[s].second];
            grid.sx[s] = grid.sorted[s].x();
            grid.sy[s] = grid.sorted[s].y();
            grid.sz[s] = grid.sorted[s].z();
        }
    });
}

std::size_t count_cells(const std::vector<std::uint64_t>& keys, int level) {
    std::size_t cells = 0;
    for (std::size_t s = 0; s < keys.size(); ++s) {
        cells += s == 0 || (keys[s] >> (3 * level)) != (keys[s - 1] >> (3 * level));
    }
    return cells;
}

// The coarsest level whose mean cell occupancy stays near `target` points.
void choose_cells(double target, MortonGrid& grid) {
    const double n = double(grid.keys.size());
    int level = 0;
    double occupancy = n / double(std::max<std::size_t>(count_cells(grid.keys, 0), 1));
    while (level < kMortonBits && occupancy < target) {
        const double next = n / double(std::max<std::size_t>(count_cells(grid.keys, level + 1), 1));
        if (next > target && next / target > target / occupancy) break;  // Previous is closer.
        ++level;
        occupancy = next;
    }
    grid.level = level;
    for (std::size_t s = 0; s < grid.keys.size(); ++s) {
        const std::uint64_t cell = grid.keys[s] >> (3 * level);
        if (grid.cell_keys.empty() || grid.cell_keys.back() != cell) {
            grid.cell_keys.push_back(cell);
            grid.cell_begin.push_back(std::uint32_t(s));
        }
    }
    grid.cell_begin.push_back(std::uint32_t(grid.keys.size()));
}

// The k best (squared distance, index) pairs seen so far, closest first, ties by index.
// A pair is one 64-bit key, distance bits above the index: squared distances are >= 0, so
// their IEEE bits order like the values and one integer comparison orders the pairs.
class TopK {
public:
    TopK(std::size_t k, float max_d2) : k_(k), max_d2_(max_d2), keys_(k + 1) {}
    // Starts over, keeping only candidates within `bound_d2` (and the radius limit).
    void clear(float bound_d2) {
        size_ = 0;
        worst_ = std::min(bound_d2, max_d2_);
        worst_key_ = pack(worst_, std::numeric_limits<std::uint32_t>::max());
    }
    float max_d2() const { return max_d2_; }
    std::size_t size() const { return size_; }
    std::size_t capacity() const { return k_; }
    float worst() const { return worst_; }
    // Cheap rejection first: most candidates fail `key > worst`.
    void offer(float d2, std::uint32_t index) {
        const std::uint64_t key = pack(d2, index);
        if (key > worst_key_) return;
        std::size_t j = size_;
        while (j > 0 && keys_[j - 1] > key) {
            keys_[j] = keys_[j - 1];
            --j;
        }
        keys_[j] = key;
        size_ = std::min(size_ + 1, k_);
        if (size_ == k_) {
            worst_key_ = keys_[k_ - 1];
            worst_ = d2_of(worst_key_);
        }
    }
    float d2(std::size_t j) const { return d2_of(keys_[j]); }
    std::uint32_t index(std::size_t j) const { return std::uint32_t(keys_[j]); }

private:
    static std::uint64_t pack(float d2, std::uint32_t index) {
        return std::uint64_t(std::bit_cast<std::uint32_t>(d2)) << 32 | index;
    }
    static float d2_of(std::uint64_t key) { return std::bit_cast<float>(std::uint32_t(key >> 32)); }

    std::size_t k_;
    float max_d2_;
    std::vector<std::uint64_t> keys_;  // k + 1 slots: an insertion may shift the k-th out.
    std::size_t size_ = 0;
    float worst_ = 0.0f;
    std::uint64_t worst_key_ = 0;
};

void write_row(const TopK& top, std::size_t row, NeighborGraph& graph) {
    for (std::size_t j = 0; j < top.size(); ++j) {
        graph.distances_sq_m2[row * graph.k + j] = top.d2(j);
        graph.indices[row * graph.k + j] = top.index(j);
    }
    graph.counts[row] = std::uint32_t(top.size());
}

constexpr std::size_t kGroup = 4;  // Candidates compared at once (one SSE register).

// Bit j set when d2[j] <= bound, for the kGroup values at d2.
unsigned within_mask(const float* d2, float bound) {
#if defined(__SSE2__)
    return unsigned(_mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(d2), _mm_set1_ps(bound))));
#else
    unsigned mask = 0;
    for (std::size_t j = 0; j < kGroup; ++j) mask |= unsigned(d2[j] <= bound) << j;
    return mask;
#endif
}

// Positions of the (2r+1)^3 block of cells around `cell`.
struct Block {
    std::vector<float> x, y, z;  // Structure of arrays: the distance loop vectorises.
    std::vector<std::uint32_t> indices;
    std::vector<float> d2;  // Padded to a multiple of kGroup.
    std::size_t size() const { return indices.size(); }
};

// The cell offsets of a (2r+1)^3 block, nearest first: the centre, faces, edges, corners.
// Candidates near the query come first, so the k-th distance tightens early and most of
// the later candidates are rejected four at a time.
std::vector<Eigen::Array3<std::int64_t>> block_offsets(int r) {
    std::vector<Eigen::Array3<std::int64_t>> offsets;
    for (int dz = -r; dz <= r; ++dz) {
        for (int dy = -r; dy <= r; ++dy) {
            for (int dx = -r; dx <= r; ++dx) offsets.emplace_back(dx, dy, dz);
        }
    }
    std::stable_sort(offsets.begin(), offsets.end(), [](const auto& a, const auto& b) {
        return a.square().sum() < b.square().sum();
    });
    return offsets;
}

void gather_block(const MortonGrid& grid, std::size_t cell, int r, Block& block) {
    static const std::vector<Eigen::Array3<std::int64_t>> kNear = block_offsets(1);
    static const std::vector<Eigen::Array3<std::int64_t>> kWide = block_offsets(2);
    block.x.clear();
    block.y.clear();
    block.z.clear();
    block.indices.clear();
    const Eigen::Array3<std::int64_t> c = demorton(grid.cell_keys[cell]);
    for (const Eigen::Array3<std::int64_t>& offset : r == 1 ? kNear : kWide) {
        const std::ptrdiff_t other = grid.find_cell(c + offset);
        if (other < 0) continue;
        for (std::uint32_t s = grid.cell_begin[other]; s < grid.cell_begin[other + 1]; ++s) {
            block.x.push_back(grid.sorted[s].x());
            block.y.push_back(grid.sorted[s].y());
            block.z.push_back(grid.sorted[s].z());
            block.indices.push_back(grid.order[s]);
        }
    }
    // Padded to whole groups of kGroup with NaN (never within any bound).
    block.d2.assign((block.size() + kGroup - 1) / kGroup * kGroup,
                    std::numeric_limits<float>::quiet_NaN());
}

// Distance (metres) from sorted point s to the outside of the (2r+1)^3 block of cells
// around its cell: every point closer than that lies in the block.
double block_reach_m(const MortonGrid& grid, std::size_t cell, int r, std::uint32_t s) {
    const double side = double(std::int64_t(1) << grid.level);
    const Eigen::Array3d lo = demorton(grid.cell_keys[cell]).cast<double>() * side;
    const Eigen::Array3d u = grid.lattice(grid.sorted[s]).array();
    const double margin = std::max(((u - lo).min(lo + side - u)).minCoeff(), 0.0);
    return (double(r) * side + margin) / grid.units_per_m * (1.0 - 1e-6);
}

float max_distance_sq(const NeighborGraphConfig& config) {
    return config.max_radius_m > 0.0f ? config.max_radius_m * config.max_radius_m
                                      : std::numeric_limits<float>::infinity();
}

// Offers the candidates within `bound_d2`: groups of four are compared at once against the
// current k-th distance, so the many candidates that fail cost no branch each.
void offer_block(Block& block, const Eigen::Vector3f& q, std::uint32_t self, float bound_d2,
                 TopK& top) {
    const std::size_t m = block.size();
    for (std::size_t c = 0; c < m; ++c) {  // Vectorises.
        const float dx = block.x[c] - q.x(), dy = block.y[c] - q.y(), dz = block.z[c] - q.z();
        block.d2[c] = dx * dx + dy * dy + dz * dz;
    }
    top.clear(bound_d2);
    for (std::size_t c0 = 0; c0 < m; c0 += kGroup) {
        for (unsigned mask = within_mask(&block.d2[c0], top.worst()); mask != 0; mask &= mask - 1) {
            const std::size_t c = c0 + std::size_t(std::countr_zero(mask));
            if (block.indices[c] != self) top.offer(block.d2[c], block.indices[c]);
        }
    }
}

// Nearest neighbours of sorted point s among the block's points. `hint_d2` (the previous
// query's k-th distance, grown) filters candidates first; when fewer than k pass, the
// block is scanned again without it, so the answer is the same either way.
void scan_block(const MortonGrid& grid, std::uint32_t s, float hint_d2, Block& block, TopK& top) {
    const Eigen::Vector3f q = grid.sorted[s];
    offer_block(block, q, grid.order[s], hint_d2, top);
    if (top.size() < top.capacity() && hint_d2 < top.max_d2()) {
        offer_block(block, q, grid.order[s], top.max_d2(), top);
    }
}

// Whether `top`, found in the (2r+1)^3 block around `cell`, is provably the exact answer
// for sorted point s: its k-th neighbour (or the radius limit) lies within the block.
bool proven(const MortonGrid& grid, std::size_t cell, int r, std::uint32_t s, const TopK& top) {
    const double reach = block_reach_m(grid, cell, r, s);
    const bool full = top.size() == top.capacity();
    const double needed = full ? double(top.worst()) : double(top.max_d2());
    return needed <= reach * reach;
}

bool too_dense(const Block& block, std::size_t k) {  // Piles of duplicates: fall back.
    return block.size() > 64 * k + 1024;
}

// One worker's scratch: the 3x3x3 block of the current cell and, loaded only for rows it
// cannot prove (borders, sparse spots), the 5x5x5 block.
struct Scratch {
    Block near, wide;
    std::size_t wide_cell = std::numeric_limits<std::size_t>::max();
};

// Answers the points of `cell` from its blocks; rows they cannot prove exact get flagged.
void answer_cell(const MortonGrid& grid, std::size_t cell, const NeighborGraphConfig& config,
                 Scratch& scratch, NeighborGraph& graph, std::vector<std::uint8_t>& fallback) {
    gather_block(grid, cell, 1, scratch.near);
    const bool dense = too_dense(scratch.near, graph.k);
    TopK top(graph.k, max_distance_sq(config));
    float hint_d2 = std::numeric_limits<float>::infinity();
    for (std::uint32_t s = grid.cell_begin[cell]; s < grid.cell_begin[cell + 1]; ++s) {
        const std::uint32_t row = grid.order[s];
        if (dense) {
            fallback[row] = 1;
            continue;
        }
        scan_block(grid, s, hint_d2, scratch.near, top);
        if (top.size() == graph.k) hint_d2 = kHintGrowth * top.worst();
        if (!proven(grid, cell, 1, s, top)) {
            if (scratch.wide_cell != cell) gather_block(grid, cell, 2, scratch.wide);
            scratch.wide_cell = cell;
            const bool wide_dense = too_dense(scratch.wide, graph.k);
            if (!wide_dense) scan_block(grid, s, top.max_d2(), scratch.wide, top);
            if (wide_dense || !proven(grid, cell, 2, s, top)) {
                fallback[row] = 1;
                continue;
            }
        }
        write_row(top, row, graph);
    }
}

// Exact answer for one row by a linear scan of all finite points.
void brute_force_row(const MortonGrid& grid, std::uint32_t row, const Eigen::Vector3f& q, TopK& top,
                     NeighborGraph& graph) {
    constexpr std::size_t kChunk = 1024;  // A multiple of kGroup.
    std::array<float, kChunk> d2;
    top.clear(top.max_d2());
    const std::size_t n = grid.sorted.size();
    for (std::size_t begin = 0; begin < n; begin += kChunk) {
        const std::size_t m = std::min(kChunk, n - begin);
        for (std::size_t c = 0; c < m; ++c) {  // Vectorises; same rounding as offer_block.
            const float dx = grid.sx[begin + c] - q.x(), dy = grid.sy[begin + c] - q.y(),
                        dz = grid.sz[begin + c] - q.z();
            d2[c] = dx * dx + dy * dy + dz * dz;
        }
        std::fill(d2.begin() + std::ptrdiff_t(m), d2.end(),
                  std::numeric_limits<float>::quiet_NaN());
        for (std::size_t c0 = 0; c0 < m; c0 += kGroup) {
            for (unsigned mask = within_mask(&d2[c0], top.worst()); mask != 0; mask &= mask - 1) {
                const std::size_t c = c0 + std::size_t(std::countr_zero(mask));
                if (grid.order[begin + c] != row) top.offer(d2[c], grid.order[begin + c]);
            }
        }
    }
    write_row(top, row, graph);
}

// Exact answers for the flagged rows: a linear scan when they are few (building a k-d
// tree costs about as much as kBruteForceRows scans), else k-d tree queries.
void answer_fallbacks(std::span<const Eigen::Vector3f> points, const MortonGrid& grid,
                      const NeighborGraphConfig& config, const std::vector<std::uint8_t>& flags,
                      NeighborGraph& graph) {
    constexpr std::size_t kBruteForceRows = 256;
    std::vector<std::uint32_t> rows;
    for (std::size_t i = 0; i < flags.size(); ++i) {
        if (flags[i]) rows.push_back(std::uint32_t(i));
    }
    graph.num_exact_fallbacks = rows.size();
    if (rows.empty()) return;
    const float max_d2 = max_distance_sq(config);
    if (rows.size() <= kBruteForceRows) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 8), [&](auto r) {
            TopK top(graph.k, max_d2);
            for (std::size_t j = r.begin(); j < r.end(); ++j) {
                brute_force_row(grid, rows[j], points[rows[j]], top, graph);
            }
        });
        return;
    }
    const KdTree tree(grid.sorted);  // Finite points only; map back through grid.order.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows.size(), 64), [&](const auto& r) {
        std::vector<Neighbor> found;
        TopK top(graph.k, max_d2);
        for (std::size_t j = r.begin(); j < r.end(); ++j) {
            const std::uint32_t row = rows[j];
            tree.knn(points[row], graph.k + 1, found);
            top.clear(max_d2);
            for (const Neighbor& n : found) {
                const std::uint32_t index = grid.order[n.index];
                if (index != row) top.offer(n.distance_sq_m2, index);
            }
            write_row(top, row, graph);
        }
    });
}

}  // namespace

NeighborGraph build_neighbor_graph(std::span<const Eigen::Vector3f> points,
                                   const NeighborGraphConfig& config) {
    assert(points.size() < std::numeric_limits<std::uint32_t>::max());
    NeighborGraph graph;
    graph.k = std::size_t(std::max(config.k_neighbors, 1));
    graph.indices.assign(points.size() * graph.k, 0);
    graph.distances_sq_m2.assign(points.size() * graph.k, 0.0f);
    graph.counts.assign(points.size(), 0);
    MortonGrid grid;
    sort_points(points, grid);
    if (grid.keys.empty()) return graph;
    choose_cells(0.5 * double(graph.k + 1), grid);
    std::vector<std::uint8_t> fallback(points.size(), 0);
    const std::size_t num_cells = grid.cell_keys.size();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_cells, 16), [&](const auto& r) {
        Scratch scratch;
        for (std::size_t cell = r.begin(); cell < r.end(); ++cell) {
            answer_cell(grid, cell, config, scratch, graph, fallback);
        }
    });
    answer_fallbacks(points, grid, config, fallback, graph);
    return graph;
}

}  // namespace anascan
