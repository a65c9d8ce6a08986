#pragma once
/// @file
/// Density clustering's per-texel passes sixteen fragments at a time (placement/clustered.hpp): the
/// depth range, the two k-means sums and the assignment of fragments to bins. Each lane does the
/// scalar pass's own IEEE operations, and the k-means sums are integers (fixed point), whose order
/// changes nothing, so the texel's state and layers are the scalar ones bit for bit.

#include <hairshadow/placement/assign_each.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

namespace hairshadow::detail {

/// Density clustering's k-means sums are fixed point with 2^36 units to the unit (clustered::fixed_sum).
inline constexpr double cluster_fixed_scale = 68719476736.0;

#if HAIRSHADOW_AVX512_WALK
namespace avx512 {

static_assert(sizeof(optical_fragment) == 2 * sizeof(float), "optical_fragment is loaded as pairs of floats");

/// Sixteen of a texel's fragments from `f` (the first `remaining`, where fewer are left): their depths
/// and optical depths, zero past the end. Returns the lanes that hold a fragment.
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __mmask16 load_fragments(const optical_fragment* f, std::size_t remaining, __m512& depth,
                                                         __m512& optical) noexcept {
    const auto* floats = reinterpret_cast<const float*>(f);
    const std::size_t n = std::min<std::size_t>(remaining, 16);
    const __m512 front = _mm512_maskz_loadu_ps(first_lanes(2 * n), floats);
    const __m512 back = n > 8 ? _mm512_maskz_loadu_ps(first_lanes(2 * n - 16), floats + 16) : _mm512_setzero_ps();
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    depth = _mm512_permutex2var_ps(front, even, back);
    optical = _mm512_permutex2var_ps(front, _mm512_add_epi32(even, _mm512_set1_epi32(1)), back);
    return first_lanes(n);
}

/// detail::depth_range_of: the same nearest and furthest depth. The lanes are reduced in another
/// order than the fragments come, which can change only the sign of a zero, so a range that ends
/// at zero is reduced again in order.
HAIRSHADOW_AVX512_TARGET inline depth_extent texel_depth_range(std::span<const optical_fragment> fragments) noexcept {
    __m512 nearest = _mm512_set1_ps(fragments[0].depth), furthest = nearest;
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        nearest = _mm512_mask_mov_ps(nearest, lanes & _mm512_cmp_ps_mask(depth, nearest, _CMP_LT_OQ), depth);
        furthest = _mm512_mask_mov_ps(furthest, lanes & _mm512_cmp_ps_mask(furthest, depth, _CMP_LT_OQ), depth);
    }
    alignas(64) float near_lanes[16], far_lanes[16];
    _mm512_store_ps(near_lanes, nearest), _mm512_store_ps(far_lanes, furthest);
    depth_extent range{near_lanes[0], far_lanes[0]};
    for (int i = 1; i < 16; ++i) range.nearest = std::min(range.nearest, near_lanes[i]), range.furthest = std::max(range.furthest, far_lanes[i]);
    if (range.nearest == 0.0f || range.furthest == 0.0f) return depth_range_of(fragments);
    return range;
}

/// Per lane, the nearest of the `usable` centres by |depth - centre| in float, the first of equals:
/// clustered::nearest (the first usable one for a NaN depth, 0 where none is usable).
template <int K>
HAIRSHADOW_AVX512_TARGET inline __m512i nearest_centre(__m512 depth, const float* centres, std::uint32_t usable) noexcept {
    __m512i best = _mm512_setzero_si512();
    __m512 best_distance = _mm512_setzero_ps();
    bool first = true;
    for (int j = 0; j < K; ++j) {
        if (!(usable >> j & 1u)) continue;
        const __m512 distance = _mm512_abs_ps(_mm512_sub_ps(depth, _mm512_set1_ps(centres[j])));
        const __mmask16 nearer = first ? __mmask16(0xFFFF) : _mm512_cmp_ps_mask(distance, best_distance, _CMP_LT_OQ);
        best = _mm512_mask_mov_epi32(best, nearer, _mm512_set1_epi32(j));
        best_distance = _mm512_mask_mov_ps(best_distance, nearer, distance);
        first = false;
    }
    return best;
}

/// clustered::fixed_sum (x in units of 2^-36, truncated toward zero) in every lane. Exact while
/// |x| < 2^15 (2^51 units): where one of `lanes` is not, `in_range` is cleared.
HAIRSHADOW_AVX512_TARGET inline __m512i fixed_terms(__m512d x, __mmask8 lanes, bool& in_range) noexcept {
    const __m512d units = _mm512_mul_pd(x, _mm512_set1_pd(cluster_fixed_scale));
    in_range &= _mm512_mask_cmp_pd_mask(lanes, _mm512_abs_pd(units), _mm512_set1_pd(0x1p51), _CMP_NLT_UQ) == 0;
    // A whole number below 2^51 in magnitude plus 1.5 * 2^52 is exact, and its bits are those of
    // 1.5 * 2^52 plus the number.
    const __m512d whole = _mm512_roundscale_pd(units, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
    const __m512d magic = _mm512_set1_pd(0x1.8p52);
    return _mm512_sub_epi64(_mm512_castpd_si512(_mm512_add_pd(whole, magic)), _mm512_castpd_si512(magic));
}

/// Lanes 8 * half to 8 * half + 7 of x, in double.
HAIRSHADOW_AVX512_TARGET inline __m512d widen_half(__m512 x, int half) noexcept {
    const __m256 part = half == 0 ? _mm512_castps512_ps256(x) : _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(x), 1));
    return _mm512_cvtps_pd(part);
}

/// One of clustered::prepare_texel's k-means passes: for every fragment, the nearest of the `usable`
/// centres j takes fixed_sum(b) into weight[j] and into sum[j] fixed_sum(b * depth) (the first pass)
/// or, with Spread, fixed_sum(b * d * d) for d = depth - centre (the second). Sums of clusters that
/// are not usable are left 0. Returns false, with the sums unfinished, where a term is too large for
/// the vector's exact conversion (|term| >= 2^15), which only absurd depths make.
template <int K, bool Spread>
    requires(K <= 16)
HAIRSHADOW_AVX512_TARGET inline bool add_cluster_sums(std::span<const optical_fragment> fragments, const float* centres, std::uint32_t usable,
                                                      std::int64_t* weight, std::int64_t* sum) noexcept {
    __m512i weights[K], sums[K];
    for (int j = 0; j < K; ++j) weights[j] = sums[j] = _mm512_setzero_si512();
    bool in_range = true;
    alignas(64) double centre_values[16] = {};
    for (int j = 0; j < K; ++j) centre_values[j] = double(centres[j]);
    const __m512d centres_low = _mm512_load_pd(centre_values), centres_high = _mm512_load_pd(centre_values + 8);
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        const __m512i nearest = nearest_centre<K>(depth, centres, usable);
        for (int half = 0; half < 2; ++half) {
            const auto half_lanes = __mmask8(lanes >> (8 * half));
            if (half_lanes == 0) break;
            const __m512d b = widen_half(optical, half), d = widen_half(depth, half);
            const __m512i weight_term = fixed_terms(b, half_lanes, in_range);
            __m512i sum_term;
            if constexpr (Spread) {
                // Each lane's own centre, picked from the (up to sixteen) centres by its index.
                const __m512i index = _mm512_cvtepi32_epi64(half == 0 ? _mm512_castsi512_si256(nearest) : _mm512_extracti64x4_epi64(nearest, 1));
                const __m512d from_centre = _mm512_sub_pd(d, _mm512_permutex2var_pd(centres_low, index, centres_high));
                sum_term = fixed_terms(_mm512_mul_pd(_mm512_mul_pd(b, from_centre), from_centre), half_lanes, in_range);
            } else {
                sum_term = fixed_terms(_mm512_mul_pd(b, d), half_lanes, in_range);
            }
            for (int j = 0; j < K; ++j) {
                if (!(usable >> j & 1u)) continue;
                const auto mine = __mmask8(__mmask8(_mm512_cmpeq_epi32_mask(nearest, _mm512_set1_epi32(j)) >> (8 * half)) & half_lanes);
                weights[j] = _mm512_mask_add_epi64(weights[j], mine, weights[j], weight_term);
                sums[j] = _mm512_mask_add_epi64(sums[j], mine, sums[j], sum_term);
            }
        }
    }
    for (int j = 0; j < K; ++j) weight[j] = _mm512_reduce_add_epi64(weights[j]), sum[j] = _mm512_reduce_add_epi64(sums[j]);
    return in_range;
}

/// clustered::texel_assigner for every fragment: the first `filled` bin [lo, hi) holding the depth
/// (or equal to a bin of no width), else the nearest usable mean.
template <int K>
HAIRSHADOW_AVX512_TARGET inline void assign_to_bins(std::span<const optical_fragment> fragments, const float* lo, const float* hi, std::uint32_t filled,
                                                    const float* means, std::uint32_t usable, std::int32_t* layers) noexcept {
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        __m512i layer = nearest_centre<K>(depth, means, usable);
        for (int j = K - 1; j >= 0; --j) { // the first bin holding the depth is the last to write
            if (!(filled >> j & 1u)) continue;
            const __m512 low = _mm512_set1_ps(lo[j]);
            __mmask16 inside = _mm512_cmp_ps_mask(depth, _mm512_set1_ps(hi[j]), _CMP_LT_OQ);
            if (lo[j] == hi[j]) inside |= _mm512_cmp_ps_mask(depth, low, _CMP_EQ_OQ);
            inside &= _mm512_cmp_ps_mask(depth, low, _CMP_GE_OQ);
            layer = _mm512_mask_mov_epi32(layer, inside, _mm512_set1_epi32(j));
        }
        _mm512_mask_storeu_epi32(layers + i, lanes, layer);
    }
}

} // namespace avx512
#endif

} // namespace hairshadow::detail
