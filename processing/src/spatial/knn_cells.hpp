#pragma once
/// \file
/// Private to the k-NN graph (neighbor_graph.cpp): the grid of cubic cells the points are
/// bucketed into, and the blocks of cells each query is answered from.

#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "anascan/processing/spatial/neighbor_graph.hpp"
#include "spatial/knn_select.hpp"

namespace anascan::knn_detail {

// Rows the 3x3x3 block cannot prove are retried on the 5x5x5 block, and so on up to
// (2 kMaxRing + 1)^3; the few left (outliers) are answered by linear scans or a k-d tree.
constexpr int kMaxRing = 4;

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

// Where each row of the 3x3x3 block stood in the sorted cells for the previous cell: a
// worker answers cells in increasing order, and the first key of each row (when the row
// lies in the grid) then only grows, so rows are found by stepping forward from there
// instead of by hash look-ups.
struct RowCursors {
    std::array<std::size_t, 9> at{};
    std::array<bool, 9> started{};
};

/// Finite points as arrays, in index order, with their original indices.
Candidates finite_points(std::span<const Eigen::Vector3f> points);

/// Cell side from the sampled k-th neighbour distance (or the radius limit, when
/// smaller), and the grid's extent.
void size_cells(const Candidates& finite, const NeighborGraphConfig& config, std::size_t k,
                CellGrid& grid);

/// Sorts the finite points by cell (ties by index: deterministic) and numbers the cells.
void sort_into_cells(const Candidates& finite, CellGrid& grid);

/// The points of the (2r+1)^3 block of cells around `cell`, one contiguous run per row,
/// nearest rows first; with `cursors` (3x3x3 blocks of cells in increasing order) the rows
/// are found by stepping forward.
void gather_block(const CellGrid& grid, std::size_t cell, int r, Candidates& block,
                  RowCursors* cursors = nullptr);

/// Distance (metres) from sorted point s to the outside of the (2r+1)^3 block of cells
/// around its cell: every point closer than that lies in the block.
double block_reach_m(const CellGrid& grid, std::size_t cell, int r, std::size_t s);

}  // namespace anascan::knn_detail
