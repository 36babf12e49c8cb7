#pragma once
/// \file
/// Private selection primitives of the k-NN graph (neighbor_graph.cpp): candidate arrays,
/// a top k of packed (distance, index) keys, and branch-free compaction and ranking of
/// the candidates within a bound, four at a time with SSE2 where available; the ranking
/// also has AVX2 versions, chosen at run time (detail::cpu_has_avx2), that give the same ranks.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace anascan::knn_detail {

constexpr std::size_t kGroup = 4;             // Candidates compared at once (one SSE register).
constexpr std::size_t kWideGroup = 8;         // With AVX2 (one AVX register).
constexpr std::size_t kPadding = kWideGroup;  // Readable entries past a block's end, + 1.

// Bit j set when d2[j] <= bound, for the kGroup values at d2.
inline unsigned within_mask(const float* d2, float bound) {
#if defined(__SSE2__)
    return unsigned(_mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(d2), _mm_set1_ps(bound))));
#else
    unsigned mask = 0;
    for (std::size_t j = 0; j < kGroup; ++j) mask |= unsigned(d2[j] <= bound) << j;
    return mask;
#endif
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
    // Starts over with the n pairs of known ranks (0 .. n - 1, all different): those
    // ranked below k, in their places.
    void place_ranked(const float* d2, const std::uint32_t* index, const std::int32_t* rank,
                      std::size_t n) {
        std::uint64_t* const keys = keys_.data();
        const std::size_t k = k_;              // A copy: a key store could be taken to change k_.
        for (std::size_t c = 0; c < n; ++c) {  // Ranks from k on land in the spare slot k:
            keys[std::min(std::size_t(rank[c]), k)] = pack(d2[c], index[c]);  // no branch.
        }
        clear(max_d2_);
        size_ = std::min(n, k_);
        if (size_ == k_) {
            worst_key_ = keys_[k_ - 1];
            worst_ = d2_of(worst_key_);
        }
    }
    float d2(std::size_t j) const { return d2_of(keys_[j]); }
    const std::uint64_t* keys() const { return keys_.data(); }  // size() packed pairs.
    std::uint32_t index(std::size_t j) const { return std::uint32_t(keys_[j]); }

    static std::uint64_t pack(float d2, std::uint32_t index) {
        return std::uint64_t(std::bit_cast<std::uint32_t>(d2)) << 32 | index;
    }

private:
    static float d2_of(std::uint64_t key) { return std::bit_cast<float>(std::uint32_t(key >> 32)); }

    std::size_t k_;
    float max_d2_;
    std::vector<std::uint64_t> keys_;  // k + 1 slots: an insertion may shift the k-th out.
    std::size_t size_ = 0;
    float worst_ = 0.0f;
    std::uint64_t worst_key_ = 0;
};

// Leaves new elements of trivial type uninitialised (resize then writes nothing): the
// arrays below are filled right after they grow.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UninitialisedAllocator<U>;
    };
    UninitialisedAllocator() = default;
    template <class U>
    UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};
template <class T>
using Array = std::vector<T, UninitialisedAllocator<T>>;

// Candidate positions as arrays (the distance loop vectorises) with their point indices.
struct Candidates {
    Array<float> x, y, z;
    Array<std::uint32_t> indices;
    std::size_t origin = 0;  // Of a block: where the first point of its centre cell is.
    // Of a 3x3x3 block: per row of cells, its (dy, dz) and where its cells x - 1, x, x + 1
    // begin and the last ends, so that a query can skip the cells it cannot reach.
    struct Row {
        std::int64_t dy = 0, dz = 0;
        std::array<std::uint32_t, 4> at{};
    };
    std::vector<Row> rows;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> runs;  // Of a block: copied from.
    std::size_t padding = 0;  // Entries past the last point (pad).
    std::size_t size() const { return indices.size() - padding; }
    void clear() {
        x.clear();
        y.clear();
        z.clear();
        indices.clear();
        rows.clear();
        runs.clear();
        padding = 0;
    }
    // Sets the points to the runs of `from` (`size` points in all), then pads: one pass
    // over all four arrays per run, no reallocation once the arrays have grown.
    void copy_runs(const Candidates& from, std::size_t size) {
        const std::size_t total = size + kPadding - 1;
        for (Array<float>* v : {&x, &y, &z}) v->resize(total);
        indices.resize(total);
        float *px = x.data(), *py = y.data(), *pz = z.data();
        std::uint32_t* pi = indices.data();
        const float *fx = from.x.data(), *fy = from.y.data(), *fz = from.z.data();
        const std::uint32_t* fi = from.indices.data();
        for (const auto& [begin, end] : runs) {
            px = std::copy(fx + begin, fx + end, px);
            py = std::copy(fy + begin, fy + end, py);
            pz = std::copy(fz + begin, fz + end, pz);
            pi = std::copy(fi + begin, fi + end, pi);
        }
        std::fill(x.begin() + std::ptrdiff_t(size), x.end(),
                  std::numeric_limits<float>::quiet_NaN());
        std::fill(y.begin() + std::ptrdiff_t(size), y.end(),
                  std::numeric_limits<float>::quiet_NaN());
        std::fill(z.begin() + std::ptrdiff_t(size), z.end(),
                  std::numeric_limits<float>::quiet_NaN());
        std::fill(indices.begin() + std::ptrdiff_t(size), indices.end(), 0u);
        padding = kPadding - 1;
    }
};

// Offers candidates [begin, end) to `top` (which the caller cleared): groups of four are
// compared at once against the current k-th distance, so the many candidates that fail
// cost no branch each. `self` is never offered; `d2` is scratch.
void offer_range(const Candidates& c, std::size_t begin, std::size_t end, const Eigen::Vector3f& q,
                 std::uint32_t self, std::vector<float>& d2, TopK& top);

// Exact k nearest among all of `all` by a linear scan, in chunks (the scratch stays small).
void scan_all(const Candidates& all, const Eigen::Vector3f& q, std::uint32_t self,
              std::vector<float>& d2, TopK& top);

// Rank of each of the n entries among them (smaller distance, or equal and smaller
// index, comes first), each pair compared once, four at a time: no branch depends on the
// data. The arrays hold n + kGroup entries; the padding (+inf, ~0) ranks last.
void rank_all(const float* d2, const std::uint32_t* index, std::size_t n, std::int32_t* rank);

// pick_range with AVX2, eight candidates at a time, compacted at once: appends the squared
// distances and point indices of the block's points [begin, end) within `bound` to d2 and
// index from slot n (room for n + end - begin + kWideGroup). Returns the new count. The
// block has kPadding - 1 readable entries past its end; the caller hides the query's own
// entry (a NaN coordinate). Needs detail::cpu_has_avx2().
std::size_t pick_compact_avx2(const Candidates& block, std::size_t begin, std::size_t end,
                              const Eigen::Vector3f& q, float bound, float* d2,
                              std::uint32_t* index, std::size_t n);

// Rank of each of the n distances by distance alone (the number of smaller ones), each
// against all, eight against eight at a time (the counts of eight entries summed across
// lanes together); returns the sum of the ranks, which is n (n - 1) / 2 exactly when no
// two distances are equal (then these are the ranks of rank_all). Needs detail::cpu_has_avx2(); d2
// holds n + 2 kGroup entries, the padding +inf; rank has room for n + 2 kGroup.
std::size_t rank_distances_avx2(const float* d2, std::size_t n, std::int32_t* rank);

// Hot, inlined into the query loop.
// The lanes of the set bits of each 4-bit mask, in order (unused lanes: 0).
alignas(16) inline constexpr std::array<std::array<std::int32_t, kGroup>, 16> kMaskLanes = [] {
    std::array<std::array<std::int32_t, kGroup>, 16> lanes{};
    for (unsigned mask = 0; mask < 16; ++mask) {
        std::size_t n = 0;
        for (unsigned lane = 0; lane < kGroup; ++lane) {
            if (mask & (1u << lane)) lanes[mask][n++] = std::int32_t(lane);
        }
    }
    return lanes;
}();

// Appends start + the lanes of `mask` to `picked` from slot n; returns the new count.
inline std::size_t append_lanes(std::size_t start, unsigned mask, std::uint32_t* picked,
                                std::size_t n) {
#if defined(__SSE2__)
    const __m128i lanes =
        _mm_add_epi32(_mm_set1_epi32(std::int32_t(start)),
                      _mm_loadu_si128(reinterpret_cast<const __m128i*>(kMaskLanes[mask].data())));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&picked[n]), lanes);
#else
    for (std::size_t lane = 0; lane < kGroup; ++lane) {
        picked[n + lane] = std::uint32_t(start + std::size_t(kMaskLanes[mask][lane]));
    }
#endif
    return n + ((0x4332322132212110ULL >> (4 * mask)) & 0xf);  // popcount(mask), no libcall.
}

#if defined(__SSE2__)
// Squared distances from q to the four entries from j, stored at d2[j]; bit l of the
// result set when entry j + l is within `bound`. Rounds as the scalar dx*dx + dy*dy + dz*dz.
inline unsigned pick_group(const float* x, const float* y, const float* z, std::size_t j, __m128 qx,
                           __m128 qy, __m128 qz, __m128 limit, float* d2) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(x + j), qx);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(y + j), qy);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(z + j), qz);
    const __m128 dist =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    _mm_storeu_ps(d2 + j, dist);
    return unsigned(_mm_movemask_ps(_mm_cmple_ps(dist, limit)));
}
#endif

// Squared distances from q to the block's points [begin, end) into d2 (same places),
// appending those within `bound` to `picked` from slot n, four at a time and without a
// branch per group. Returns the new count. d2 and picked have room for end + kGroup; the
// block's x, y, z have kGroup - 1 readable entries past end (Candidates::pad). The caller
// hides the query's own entry (a NaN coordinate: never within the bound).
inline std::size_t pick_range(const Candidates& block, std::size_t begin, std::size_t end,
                              const Eigen::Vector3f& q, float bound, float* d2,
                              std::uint32_t* picked, std::size_t n) {
    const float *x = block.x.data(), *y = block.y.data(), *z = block.z.data();
    std::size_t j0 = begin;
#if defined(__SSE2__)
    const __m128 qx = _mm_set1_ps(q.x()), qy = _mm_set1_ps(q.y()), qz = _mm_set1_ps(q.z());
    const __m128 limit = _mm_set1_ps(bound);
    for (; j0 + kGroup <= end; j0 += kGroup) {
        n = append_lanes(j0, pick_group(x, y, z, j0, qx, qy, qz, limit, d2), picked, n);
    }
    if (j0 < end) {  // The last partial group reads into the padding or the next range.
        const unsigned mask = pick_group(x, y, z, j0, qx, qy, qz, limit, d2);
        n = append_lanes(j0, mask & (0xfu >> (kGroup - (end - j0))), picked, n);
    }
#else
    for (; j0 < end; j0 += kGroup) {
        for (std::size_t j = j0; j < j0 + kGroup; ++j) {
            const float dx = x[j] - q.x(), dy = y[j] - q.y(), dz = z[j] - q.z();
            d2[j] = j < end ? dx * dx + dy * dy + dz * dz : std::numeric_limits<float>::quiet_NaN();
        }
        n = append_lanes(j0, within_mask(&d2[j0], bound), picked, n);
    }
#endif
    return n;
}

}  // namespace anascan::knn_detail
