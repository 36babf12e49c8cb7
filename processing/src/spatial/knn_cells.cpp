#include "spatial/knn_cells.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>

namespace anascan::knn_detail {
namespace {

// Cell side over the (median, sampled) distance to the k-th neighbour: ~10 points per
// cell on the bunny scans, and the 3x3x3 block around a query proves almost every row.
constexpr double kCellPerRadius = 2.0;
constexpr std::size_t kRadiusSamples = 8;  // Queries answered by brute force to size cells.

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

}  // namespace

// Finite points as arrays, in index order, copied in parallel; the rare cloud with non-finite
// points is then compacted in order.
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

void gather_block(const CellGrid& grid, std::size_t cell, int r, Candidates& block,
                  RowCursors* cursors) {
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

}  // namespace anascan::knn_detail
