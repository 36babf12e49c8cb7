#include "anascan/processing/spatial/voxel_grid.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace anascan {
namespace {

// Points grouped by voxel: `order` lists point indices voxel after voxel (voxels in key
// order, points of one voxel in input-index order); voxel r is order[starts[r], starts[r+1]).
struct SortedVoxels {
    std::vector<std::uint32_t> order;
    std::vector<std::uint32_t> starts;
};

// Sort records: a voxel key and a point index. Keys of at most 32 bits pack with the index
// into one 64-bit word (key in the high half), which halves the memory the sort moves.
struct KeyedIndex {
    std::uint64_t key = 0;
    std::uint32_t index = 0;
};
using PackedKeyIndex = std::uint64_t;

std::uint64_t key_of(const KeyedIndex& k) { return k.key; }
std::uint32_t index_of(const KeyedIndex& k) { return k.index; }
std::uint64_t key_of(PackedKeyIndex k) { return k >> 32; }
std::uint32_t index_of(PackedKeyIndex k) { return static_cast<std::uint32_t>(k); }

template <class Record>
Record make_record(std::uint64_t key, std::uint32_t index) {
    if constexpr (std::is_same_v<Record, PackedKeyIndex>) {
        return (key << 32) | index;
    } else {
        return KeyedIndex{key, index};
    }
}

bool is_finite(const Eigen::Vector3f& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

using VoxelIndex = std::array<std::int64_t, 3>;

// Voxel indices beyond this magnitude do not fit the packed key (and would overflow).
constexpr double kMaxVoxelIndex = 0x1p62;

// Integer voxel coordinates floor(p / size), as a multiply and a truncation (std::floor is a
// library call without SSE4.1). False for indices of magnitude 2^62 or more.
bool voxel_index(const Eigen::Vector3f& p, double inv_size, VoxelIndex& out) {
    for (int a = 0; a < 3; ++a) {
        const double v = static_cast<double>(p[a]) * inv_size;
        if (!(std::abs(v) < kMaxVoxelIndex)) return false;
        const auto truncated = static_cast<std::int64_t>(v);
        out[a] = truncated - (v < static_cast<double>(truncated) ? 1 : 0);
    }
    return true;
}

// How voxel indices pack into one 64-bit key: (x, y, z) relative to the minimum, x in the
// high bits, so key order is lexicographic (x, y, z) order.
struct KeyLayout {
    VoxelIndex min{};
    int shift_x = 0;
    int shift_y = 0;
    int total_bits = 0;
    bool fits = false;  // False when the cloud spans too many voxels for a 63-bit key.
};

KeyLayout plan_keys(const PointCloud& cloud, double inv_size) {
    KeyLayout layout;
    VoxelIndex min{INT64_MAX, INT64_MAX, INT64_MAX};
    VoxelIndex max{INT64_MIN, INT64_MIN, INT64_MIN};
    VoxelIndex v{};
    for (const Eigen::Vector3f& p : cloud.positions) {
        if (!is_finite(p)) continue;
        if (!voxel_index(p, inv_size, v)) return layout;
        for (int a = 0; a < 3; ++a) {
            min[a] = std::min(min[a], v[a]);
            max[a] = std::max(max[a], v[a]);
        }
    }
    layout.fits = true;
    if (min[0] > max[0]) return layout;  // No finite point: nothing to key.
    std::array<int, 3> bits{};
    for (int a = 0; a < 3; ++a) bits[a] = std::bit_width(std::uint64_t(max[a] - min[a]));
    layout.min = min;
    layout.shift_y = bits[2];
    layout.shift_x = bits[1] + bits[2];
    layout.total_bits = bits[0] + bits[1] + bits[2];
    layout.fits = layout.total_bits <= 63;  // Keeps every shift below 64.
    return layout;
}

template <class Record>
std::vector<Record> compute_keys(const PointCloud& cloud, double inv_size,
                                 const KeyLayout& layout) {
    std::vector<Record> keyed;
    keyed.reserve(cloud.size());
    VoxelIndex v{};
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const Eigen::Vector3f& p = cloud.positions[i];
        if (!is_finite(p) || !voxel_index(p, inv_size, v)) continue;
        const auto offset = [&](int a) { return std::uint64_t(v[a] - layout.min[a]); };
        const std::uint64_t key =
            (offset(0) << layout.shift_x) | (offset(1) << layout.shift_y) | offset(2);
        keyed.push_back(make_record<Record>(key, static_cast<std::uint32_t>(i)));
    }
    return keyed;
}

// Stable LSD radix sort on the key with digits of at most 11 bits (histograms of all digits
// in one read); passes where every key has the same digit are skipped. Stability keeps each
// voxel's points in input-index order.
template <class Record>
void radix_sort(std::vector<Record>& keyed, int total_bits) {
    if (total_bits == 0) return;
    const int passes = (total_bits + 10) / 11;
    const int width = (total_bits + passes - 1) / passes;
    const std::uint64_t mask = (std::uint64_t{1} << width) - 1;
    std::vector<std::size_t> offsets(static_cast<std::size_t>(passes) << width, 0);
    for (const Record& k : keyed) {
        for (int pass = 0; pass < passes; ++pass) {
            ++offsets[(std::size_t(pass) << width) + ((key_of(k) >> (pass * width)) & mask)];
        }
    }
    std::vector<Record> buffer(keyed.size());
    for (int pass = 0; pass < passes; ++pass) {
        const std::span<std::size_t> offset(offsets.data() + (std::size_t(pass) << width),
                                            std::size_t{1} << width);
        if (std::ranges::find(offset, keyed.size()) != offset.end()) continue;
        std::size_t sum = 0;
        for (std::size_t& o : offset) sum += std::exchange(o, sum);
        for (const Record& k : keyed) buffer[offset[(key_of(k) >> (pass * width)) & mask]++] = k;
        keyed.swap(buffer);
    }
}

template <class Record>
SortedVoxels sort_packed(const PointCloud& cloud, double inv_size, const KeyLayout& layout) {
    std::vector<Record> keyed = compute_keys<Record>(cloud, inv_size, layout);
    radix_sort(keyed, layout.total_bits);
    SortedVoxels voxels;
    voxels.order.reserve(keyed.size());
    voxels.starts.reserve(keyed.size() + 1);  // Only the pages written are ever touched.
    for (std::size_t i = 0; i < keyed.size(); ++i) {
        if (i == 0 || key_of(keyed[i]) != key_of(keyed[i - 1])) {
            voxels.starts.push_back(static_cast<std::uint32_t>(i));
        }
        voxels.order.push_back(index_of(keyed[i]));
    }
    voxels.starts.push_back(static_cast<std::uint32_t>(keyed.size()));
    return voxels;
}

// Fallback for clouds spanning more than 2^63 voxels (or a voxel size so small that indices
// overflow): a comparison sort on voxel coordinates held in doubles, which cannot overflow.
SortedVoxels sort_unpacked(const PointCloud& cloud, double size_m) {
    using Keyed = std::tuple<double, double, double, std::uint32_t>;
    std::vector<Keyed> keyed;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (!is_finite(cloud.positions[i])) continue;
        const Eigen::Array3d v = (cloud.positions[i].cast<double>().array() / size_m).floor();
        keyed.emplace_back(v.x(), v.y(), v.z(), static_cast<std::uint32_t>(i));
    }
    std::sort(keyed.begin(), keyed.end());
    SortedVoxels voxels;
    for (std::size_t i = 0; i < keyed.size(); ++i) {
        const auto same_voxel = [&](const Keyed& a, const Keyed& b) {
            return std::get<0>(a) == std::get<0>(b) && std::get<1>(a) == std::get<1>(b) &&
                   std::get<2>(a) == std::get<2>(b);
        };
        if (i == 0 || !same_voxel(keyed[i], keyed[i - 1])) {
            voxels.starts.push_back(static_cast<std::uint32_t>(i));
        }
        voxels.order.push_back(std::get<3>(keyed[i]));
    }
    voxels.starts.push_back(static_cast<std::uint32_t>(keyed.size()));
    return voxels;
}

using Run = std::span<const std::uint32_t>;

Eigen::Vector3f mean_vector(const std::vector<Eigen::Vector3f>& values, Run run) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::uint32_t i : run) sum += values[i].cast<double>();
    return (sum / static_cast<double>(run.size())).cast<float>();
}

// Mean direction, renormalised. When the normals cancel out, the lexicographically largest
// normal of the voxel is kept, a choice that does not depend on input order.
Eigen::Vector3f mean_normal(const std::vector<Eigen::Vector3f>& normals, Run run) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::uint32_t i : run) {
        if (is_finite(normals[i])) sum += normals[i].cast<double>();
    }
    const double norm = sum.norm();
    if (norm > 1e-9 * static_cast<double>(run.size())) return (sum / norm).cast<float>();
    Eigen::Vector3f best = normals[run.front()];
    for (std::uint32_t i : run) {
        const Eigen::Vector3f& n = normals[i];
        if (std::lexicographical_compare(best.data(), best.data() + 3, n.data(), n.data() + 3)) {
            best = n;
        }
    }
    return best;
}

Rgb8 mean_color(const std::vector<Rgb8>& colors, Run run) {
    std::array<std::uint64_t, 3> sum{};
    for (std::uint32_t i : run) {
        sum[0] += colors[i].r;
        sum[1] += colors[i].g;
        sum[2] += colors[i].b;
    }
    const std::uint64_t n = run.size();
    auto rounded = [n](std::uint64_t s) { return static_cast<std::uint8_t>((s + n / 2) / n); };
    return Rgb8{rounded(sum[0]), rounded(sum[1]), rounded(sum[2])};
}

float mean_scalar(const std::vector<float>& values, Run run) {
    double sum = 0.0;
    for (std::uint32_t i : run) sum += values[i];
    return static_cast<float>(sum / static_cast<double>(run.size()));
}

// An attribute is averaged only when it is present for every point; an inconsistent one
// is dropped rather than read out of bounds.
template <class V>
bool usable(const V& attribute, std::size_t n) {
    return n > 0 && attribute.size() == n;
}

// out[r] = mean of `values` over voxel r, one attribute at a time, prefetching the points a
// little ahead: for spatially scattered input this gather is the costly step.
template <class T, class MeanFn>
void reduce_attribute(const std::vector<T>& values, const SortedVoxels& voxels, MeanFn mean,
                      std::vector<T>& out) {
    constexpr std::size_t kPrefetchAhead = 32;
    const std::vector<std::uint32_t>& order = voxels.order;
    out.resize(voxels.starts.size() - 1);
    for (std::size_t r = 0; r < out.size(); ++r) {
        const std::size_t begin = voxels.starts[r];
        const std::size_t end = voxels.starts[r + 1];
        const std::size_t ahead_end = std::min(end + kPrefetchAhead, order.size());
        for (std::size_t k = begin + kPrefetchAhead; k < ahead_end; ++k) {
            __builtin_prefetch(&values[order[k]]);
        }
        out[r] = mean(values, Run(order.data() + begin, end - begin));
    }
}

PointCloud reduce_runs(const PointCloud& cloud, const SortedVoxels& voxels) {
    const std::size_t n = cloud.size();
    PointCloud out;
    out.origin_m = cloud.origin_m;
    reduce_attribute(cloud.positions, voxels, mean_vector, out.positions);
    if (usable(cloud.normals, n)) reduce_attribute(cloud.normals, voxels, mean_normal, out.normals);
    if (usable(cloud.colors, n)) reduce_attribute(cloud.colors, voxels, mean_color, out.colors);
    if (usable(cloud.intensity, n)) {
        reduce_attribute(cloud.intensity, voxels, mean_scalar, out.intensity);
    }
    if (usable(cloud.confidence, n)) {
        reduce_attribute(cloud.confidence, voxels, mean_scalar, out.confidence);
    }
    return out;
}

}  // namespace

PointCloud voxel_downsample(const PointCloud& cloud, const VoxelDownsampleConfig& config) {
    const double size_m = config.voxel_size_m;
    if (!(size_m > 0.0)) return cloud;
    assert(cloud.size() < std::numeric_limits<std::uint32_t>::max());
    // Step 1: a 64-bit key per finite point; step 2: group points by key; step 3: one mean
    // point per voxel. Sums of float inputs run in double, so after rounding back to float
    // the means do not depend on the order of a voxel's points (ties aside, bit for bit).
    const double inv_size = 1.0 / size_m;
    const KeyLayout layout = plan_keys(cloud, inv_size);
    const SortedVoxels voxels = !layout.fits ? sort_unpacked(cloud, size_m)
                                : layout.total_bits <= 32
                                    ? sort_packed<PackedKeyIndex>(cloud, inv_size, layout)
                                    : sort_packed<KeyedIndex>(cloud, inv_size, layout);
    return reduce_runs(cloud, voxels);
}

}  // namespace anascan
