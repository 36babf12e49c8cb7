#include "spatial/knn_select.hpp"

#include <algorithm>
#include <array>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ANASCAN_KNN_AVX2 1
#endif

namespace anascan::knn_detail {

// Offers candidates [begin, end) to `top` (which the caller cleared): groups of four are
// compared at once against the current k-th distance, so the many candidates that fail
// cost no branch each. `self` is never offered; `d2` is scratch.
void offer_range(const Candidates& c, std::size_t begin, std::size_t end, const Eigen::Vector3f& q,
                 std::uint32_t self, std::vector<float>& d2, TopK& top) {
    const std::size_t m = end - begin;
    d2.resize((m + kGroup - 1) / kGroup * kGroup);
    const float *x = c.x.data() + begin, *y = c.y.data() + begin, *z = c.z.data() + begin;
    for (std::size_t j = 0; j < m; ++j) {  // Vectorises.
        const float dx = x[j] - q.x(), dy = y[j] - q.y(), dz = z[j] - q.z();
        d2[j] = dx * dx + dy * dy + dz * dz;
    }
    std::fill(d2.begin() + std::ptrdiff_t(m), d2.end(), std::numeric_limits<float>::quiet_NaN());
    const std::uint32_t* indices = c.indices.data() + begin;
    for (std::size_t j0 = 0; j0 < m; j0 += kGroup) {
        for (unsigned mask = within_mask(&d2[j0], top.worst()); mask != 0; mask &= mask - 1) {
            const std::size_t j = j0 + std::size_t(std::countr_zero(mask));
            if (indices[j] != self) top.offer(d2[j], indices[j]);
        }
    }
}

// Exact k nearest among all of `all` by a linear scan, in chunks (the scratch stays small).
void scan_all(const Candidates& all, const Eigen::Vector3f& q, std::uint32_t self,
              std::vector<float>& d2, TopK& top) {
    constexpr std::size_t kChunk = 1024;
    top.clear(top.max_d2());
    for (std::size_t begin = 0; begin < all.size(); begin += kChunk) {
        offer_range(all, begin, std::min(begin + kChunk, all.size()), q, self, d2, top);
    }
}

// Rank of each of the n entries among them (smaller distance, or equal and smaller
// index, comes first), each pair compared once, four at a time: no branch depends on the
// data. The arrays hold n + kGroup entries; the padding (+inf, ~0) ranks last.
void rank_all(const float* d2, const std::uint32_t* index, std::size_t n, std::int32_t* rank) {
    std::fill(rank, rank + n + kGroup, 0);
#if defined(__SSE2__)
    const __m128i flip = _mm_set1_epi32(std::int32_t(0x80000000u));  // Unsigned compare.
    const __m128i one = _mm_set1_epi32(1);
    for (std::size_t c = 0; c < n; ++c) {
        const __m128 dc = _mm_set1_ps(d2[c]);
        const __m128i ic = _mm_xor_si128(_mm_set1_epi32(std::int32_t(index[c])), flip);
        __m128i before_c = _mm_setzero_si128();
        for (std::size_t j = c + 1; j < n; j += kGroup) {
            const __m128 dj = _mm_loadu_ps(d2 + j);
            const __m128i ij =
                _mm_xor_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(index + j)), flip);
            const __m128i j_first = _mm_castps_si128(_mm_or_ps(
                _mm_cmplt_ps(dj, dc),
                _mm_and_ps(_mm_cmpeq_ps(dj, dc), _mm_castsi128_ps(_mm_cmplt_epi32(ij, ic)))));
            before_c = _mm_sub_epi32(before_c, j_first);  // A true lane is -1.
            auto* rj = reinterpret_cast<__m128i*>(rank + j);
            _mm_storeu_si128(rj, _mm_add_epi32(_mm_loadu_si128(rj), _mm_add_epi32(one, j_first)));
        }
        alignas(16) std::array<std::int32_t, kGroup> lanes;
        _mm_store_si128(reinterpret_cast<__m128i*>(lanes.data()), before_c);
        rank[c] += lanes[0] + lanes[1] + lanes[2] + lanes[3];
    }
#else
    for (std::size_t c = 0; c < n; ++c) {
        for (std::size_t j = c + 1; j < n; ++j) {
            const bool j_first = d2[j] < d2[c] || (d2[j] == d2[c] && index[j] < index[c]);
            rank[j_first ? c : j] += 1;
        }
    }
#endif
}

#if defined(ANASCAN_KNN_AVX2)
// sum + (lanes of dj below dc): a true comparison lane is -1.
__attribute__((target("avx2"), always_inline)) inline __m256i count_smaller(__m256i sum, __m256 dj,
                                                                            __m256 dc) {
    return _mm256_sub_epi32(sum, _mm256_castps_si256(_mm256_cmp_ps(dj, dc, _CMP_LT_OQ)));
}

__attribute__((target("avx2"))) std::size_t rank_distances_avx2(const float* d2, std::size_t n,
                                                                std::int32_t* rank) {
    constexpr std::size_t kWide = 2 * kGroup;
    const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i total = _mm256_setzero_si256();
    for (std::size_t c = 0; c < n; c += kWide) {  // Eight entries at a time (padding: +inf).
        __m256i s0 = _mm256_setzero_si256(), s1 = s0, s2 = s0, s3 = s0, s4 = s0, s5 = s0, s6 = s0,
                s7 = s0;
        const __m256 c0 = _mm256_set1_ps(d2[c]), c1 = _mm256_set1_ps(d2[c + 1]),
                     c2 = _mm256_set1_ps(d2[c + 2]), c3 = _mm256_set1_ps(d2[c + 3]),
                     c4 = _mm256_set1_ps(d2[c + 4]), c5 = _mm256_set1_ps(d2[c + 5]),
                     c6 = _mm256_set1_ps(d2[c + 6]), c7 = _mm256_set1_ps(d2[c + 7]);
        for (std::size_t j = 0; j < n; j += kWide) {
            const __m256 dj = _mm256_loadu_ps(d2 + j);
            s0 = count_smaller(s0, dj, c0);
            s1 = count_smaller(s1, dj, c1);
            s2 = count_smaller(s2, dj, c2);
            s3 = count_smaller(s3, dj, c3);
            s4 = count_smaller(s4, dj, c4);
            s5 = count_smaller(s5, dj, c5);
            s6 = count_smaller(s6, dj, c6);
            s7 = count_smaller(s7, dj, c7);
        }
        // The lane sums of s0 .. s7 as the eight lanes of one vector.
        const __m256i a = _mm256_hadd_epi32(_mm256_hadd_epi32(s0, s1), _mm256_hadd_epi32(s2, s3));
        const __m256i b = _mm256_hadd_epi32(_mm256_hadd_epi32(s4, s5), _mm256_hadd_epi32(s6, s7));
        const __m256i ranks = _mm256_add_epi32(_mm256_permute2x128_si256(a, b, 0x20),
                                               _mm256_permute2x128_si256(a, b, 0x31));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(rank + c), ranks);
        const __m256i real = _mm256_cmpgt_epi32(_mm256_set1_epi32(std::int32_t(n - c)), lanes);
        total = _mm256_add_epi32(total, _mm256_and_si256(ranks, real));  // Not the padding.
    }
    __m128i half = _mm_add_epi32(_mm256_castsi256_si128(total), _mm256_extracti128_si256(total, 1));
    half = _mm_add_epi32(half, _mm_shuffle_epi32(half, 0x4e));
    half = _mm_add_epi32(half, _mm_shuffle_epi32(half, 0xb1));
    return std::size_t(_mm_cvtsi128_si32(half));
}

// Lane numbers of the set bits of each 8-bit mask, in order, one byte each.
alignas(64) constexpr std::array<std::uint64_t, 256> kWideMaskLanes = [] {
    std::array<std::uint64_t, 256> lanes{};
    for (unsigned mask = 0; mask < 256; ++mask) {
        unsigned n = 0;
        for (unsigned lane = 0; lane < 8; ++lane) {
            if (mask & (1u << lane)) lanes[mask] |= std::uint64_t(lane) << (8 * n++);
        }
    }
    return lanes;
}();

__attribute__((target("avx2,popcnt"))) std::size_t pick_compact_avx2(
    const Candidates& block, std::size_t begin, std::size_t end, const Eigen::Vector3f& q,
    float bound, float* d2, std::uint32_t* index, std::size_t n) {
    const float *x = block.x.data(), *y = block.y.data(), *z = block.z.data();
    const std::uint32_t* indices = block.indices.data();
    const __m256 qx = _mm256_set1_ps(q.x()), qy = _mm256_set1_ps(q.y()), qz = _mm256_set1_ps(q.z());
    const __m256 limit = _mm256_set1_ps(bound);
    for (std::size_t j = begin; j < end; j += kWideGroup) {  // The last group reads past end.
        const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(x + j), qx);
        const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(y + j), qy);
        const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(z + j), qz);
        const __m256 dist = _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
        unsigned mask = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(dist, limit, _CMP_LE_OQ)));
        if (end - j < kWideGroup) mask &= (1u << (end - j)) - 1;
        const __m256i lanes =
            _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(std::int64_t(kWideMaskLanes[mask])));
        _mm256_storeu_ps(d2 + n, _mm256_permutevar8x32_ps(dist, lanes));
        const __m256i ids = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(indices + j));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(index + n),
                            _mm256_permutevar8x32_epi32(ids, lanes));
        n += std::size_t(_mm_popcnt_u32(mask));
    }
    return n;
}
#else
std::size_t pick_compact_avx2(const Candidates&, std::size_t, std::size_t, const Eigen::Vector3f&,
                              float, float*, std::uint32_t*, std::size_t n) {
    return n;
}
std::size_t rank_distances_avx2(const float*, std::size_t, std::int32_t*) { return 0; }
#endif

}  // namespace anascan::knn_detail
