#pragma once
/// @file
/// Density clustering's per-texel passes sixteen fragments at a time (placement/clustered.hpp): the
/// depth range, the two k-means sums and the assignment of fragments to bins. Each lane does the
/// scalar pass's own IEEE operations, and the k-means sums are integers (fixed point), whose order
/// changes nothing, so the texel's state and layers are the scalar ones bit for bit. A texel comes as
/// optical fragments, or, where its fragments share one optical depth, as their depths alone (half
/// the bytes to group and to load).

#include <hairshadow/placement/detail/assign_each.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <span>
#include <type_traits>

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

/// load_fragments for a texel's depths alone (fragments of one optical depth, grouped without it:
/// tile_fragments::group_depths): the depths, and optical depths of zero, which the passes for one
/// optical depth do not read.
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __mmask16 load_fragments(const float* depths, std::size_t remaining, __m512& depth,
                                                                               __m512& optical) noexcept {
    const __mmask16 lanes = first_lanes(remaining);
    depth = _mm512_maskz_loadu_ps(lanes, depths);
    optical = _mm512_setzero_ps();
    return lanes;
}

/// A texel's fragments for the vector passes: optical_fragment, or float where only depths are kept.
template <class Fragment>
concept texel_fragment = std::is_same_v<Fragment, optical_fragment> || std::is_same_v<Fragment, float>;

/// A texel's depth range and whether all its fragments share the first one's optical depth.
struct texel_scan {
    depth_extent range;
    bool one_optical_depth;
};

/// detail::texel_extent_of: the same nearest and furthest depth, and whether every optical depth equals
/// the first (as floats: a zero of either sign makes the same fixed-point terms; depths alone share
/// one by construction). The lanes are reduced in another order than the fragments come, which can
/// change only the sign of a zero, so a range that ends at zero is reduced again in order.
template <texel_fragment Fragment>
HAIRSHADOW_AVX512_TARGET inline texel_scan texel_scan_of(std::span<const Fragment> fragments) noexcept {
    constexpr bool depths_alone = std::is_same_v<Fragment, float>;
    __m512 nearest = _mm512_set1_ps(depth_of(fragments[0])), furthest = nearest;
    __m512 first_optical = _mm512_setzero_ps();
    if constexpr (!depths_alone) first_optical = _mm512_set1_ps(fragments[0].optical_depth);
    __mmask16 other_optical = 0;
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        nearest = _mm512_mask_mov_ps(nearest, lanes & _mm512_cmp_ps_mask(depth, nearest, _CMP_LT_OQ), depth);
        furthest = _mm512_mask_mov_ps(furthest, lanes & _mm512_cmp_ps_mask(furthest, depth, _CMP_LT_OQ), depth);
        if constexpr (!depths_alone) other_optical |= _mm512_mask_cmp_ps_mask(lanes, optical, first_optical, _CMP_NEQ_UQ);
    }
    // vminps and vmaxps return their second operand where either is NaN, and every lane starts at
    // the first depth, so a NaN there stays, as in texel_extent_of; a later NaN never enters a lane.
    depth_extent range{_mm512_reduce_min_ps(nearest), _mm512_reduce_max_ps(furthest)};
    if (range.nearest == 0.0f || range.furthest == 0.0f) range = texel_extent_of(fragments);
    return {range, other_optical == 0};
}

/// Per lane, the nearest of the `usable` centres by |depth - centre| in float, the first of equals:
/// clustered::nearest (the first usable one for a NaN depth, 0 where none is usable). The running
/// least distance is a vminps, which keeps its second operand unless the first is less, as the scalar
/// comparison does; the index follows off that chain, so the steps overlap.
template <int K>
    requires(K <= 16)
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512i nearest_centre(__m512 depth, const float* centres, std::uint32_t usable) noexcept {
    usable &= (1u << K) - 1u;
    if (usable == 0) return _mm512_setzero_si512();
    const int first = std::countr_zero(usable);
    __m512i best = _mm512_set1_epi32(first);
    __m512 best_distance = _mm512_abs_ps(_mm512_sub_ps(depth, _mm512_set1_ps(centres[first])));
    for (int j = 1; j < K; ++j) {
        if (j <= first || !(usable >> j & 1u)) continue;
        const __m512 distance = _mm512_abs_ps(_mm512_sub_ps(depth, _mm512_set1_ps(centres[j])));
        best = _mm512_mask_mov_epi32(best, _mm512_cmp_ps_mask(distance, best_distance, _CMP_LT_OQ), _mm512_set1_epi32(j));
        best_distance = _mm512_min_ps(distance, best_distance);
    }
    return best;
}

/// clustered::fixed_sum (x in units of 2^-36, truncated toward zero) in every lane. Exact while
/// |x| < 2^15 (2^51 units): where one of `lanes` is not, its bit is set in `too_large`.
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512i fixed_terms(__m512d x, __mmask8 lanes, __mmask8& too_large) noexcept {
    const __m512d units = _mm512_mul_pd(x, _mm512_set1_pd(cluster_fixed_scale));
    too_large |= _mm512_mask_cmp_pd_mask(lanes, _mm512_abs_pd(units), _mm512_set1_pd(0x1p51), _CMP_NLT_UQ);
    // A whole number below 2^51 in magnitude plus 1.5 * 2^52 is exact, and its bits are those of
    // 1.5 * 2^52 plus the number.
    const __m512d whole = _mm512_roundscale_pd(units, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
    const __m512d magic = _mm512_set1_pd(0x1.8p52);
    return _mm512_sub_epi64(_mm512_castpd_si512(_mm512_add_pd(whole, magic)), _mm512_castpd_si512(magic));
}

/// Lanes 8 * half to 8 * half + 7 of x, in double.
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512d widen_half(__m512 x, int half) noexcept {
    const __m256 part = half == 0 ? _mm512_castps512_ps256(x) : _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(x), 1));
    return _mm512_cvtps_pd(part);
}

/// Lane j: the sum of v[j]'s eight lanes, for eight vectors at once. Three rounds of pairing halve the
/// lanes per vector; eight separate reductions take about three times the instructions (counted), as
/// many as a texel's k-means pass over a few dozen fragments.
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512i lane_sums(const __m512i* v) noexcept {
    // 128-bit block b of pair[i]: v[2i]'s and v[2i+1]'s lanes 2b and 2b + 1, summed.
    __m512i pair[4];
    for (int i = 0; i < 4; ++i)
        pair[i] = _mm512_add_epi64(_mm512_unpacklo_epi64(v[2 * i], v[2 * i + 1]), _mm512_unpackhi_epi64(v[2 * i], v[2 * i + 1]));
    // Blocks of quad[i]: v[4i] and v[4i+1] over lanes 0-3, then 4-7; v[4i+2] and v[4i+3] likewise.
    __m512i quad[2];
    for (int i = 0; i < 2; ++i)
        quad[i] = _mm512_add_epi64(_mm512_shuffle_i64x2(pair[2 * i], pair[2 * i + 1], _MM_SHUFFLE(2, 0, 2, 0)),
                                   _mm512_shuffle_i64x2(pair[2 * i], pair[2 * i + 1], _MM_SHUFFLE(3, 1, 3, 1)));
    return _mm512_add_epi64(_mm512_shuffle_i64x2(quad[0], quad[1], _MM_SHUFFLE(2, 0, 2, 0)),
                            _mm512_shuffle_i64x2(quad[0], quad[1], _MM_SHUFFLE(3, 1, 3, 1)));
}

/// One of clustered::prepare_texel's k-means passes: for every fragment, the nearest of the `usable`
/// centres j takes fixed_sum(b) into weight[j] and into sum[j] fixed_sum(b * depth) (the first pass)
/// or, with Spread, fixed_sum(b * (depth - centre)^2), the square in float (the second). Sums of
/// clusters that are not usable are left 0. With OneOpticalDepth, every fragment's b is the first one's
/// (texel_scan_of), and weight[j] is fixed_sum(b) times the fragments j takes: the same integer, with
/// no conversion per fragment. Returns false, with the sums unfinished, where a term is too large for the
/// vector's exact conversion (|term| >= 2^15), which only absurd depths make. `first_optical` is the
/// first fragment's b, the only one read with OneOpticalDepth (which depths alone need: there, the b
/// every fragment has).
template <int K, bool Spread, bool OneOpticalDepth, texel_fragment Fragment>
    requires(K <= 16 && (OneOpticalDepth || std::is_same_v<Fragment, optical_fragment>))
HAIRSHADOW_AVX512_TARGET inline bool add_cluster_sums(std::span<const Fragment> fragments, float first_optical, const float* centres,
                                                      std::uint32_t usable, std::int64_t* weight, std::int64_t* sum) noexcept {
    // Per cluster, eight lanes of weight (with OneOpticalDepth, of fragments taken) and of sum terms.
    __m512i weights[K], sums[K];
    for (int j = 0; j < K; ++j) weights[j] = sums[j] = _mm512_setzero_si512();
    __mmask8 too_large = 0;
    const __m512d one_optical = _mm512_set1_pd(double(first_optical));
    const __m512 centre_floats = _mm512_maskz_loadu_ps(__mmask16((1u << K) - 1u), centres);
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        const __m512i nearest = nearest_centre<K>(depth, centres, usable);
        // The factor that multiplies b: the depth, or (Spread) clustered::squared_distance to the
        // lane's own centre, picked from the (up to sixteen) centres by its index, in float.
        __m512 factor = depth;
        if constexpr (Spread) {
            const __m512 from_centre = _mm512_sub_ps(depth, _mm512_permutexvar_ps(nearest, centre_floats));
            factor = _mm512_mul_ps(from_centre, from_centre);
        }
        for (int half = 0; half < 2; ++half) {
            const auto half_lanes = __mmask8(lanes >> (8 * half));
            if (half_lanes == 0) break;
            const __m512d b = OneOpticalDepth ? one_optical : widen_half(optical, half);
            const __m512i weight_term = OneOpticalDepth ? _mm512_set1_epi64(1) : fixed_terms(b, half_lanes, too_large);
            const __m512i sum_term = fixed_terms(_mm512_mul_pd(b, widen_half(factor, half)), half_lanes, too_large); // exact: two floats
            for (int j = 0; j < K; ++j) {
                if (!(usable >> j & 1u)) continue;
                const auto mine = __mmask8(__mmask8(_mm512_cmpeq_epi32_mask(nearest, _mm512_set1_epi32(j)) >> (8 * half)) & half_lanes);
                weights[j] = _mm512_mask_add_epi64(weights[j], mine, weights[j], weight_term);
                sums[j] = _mm512_mask_add_epi64(sums[j], mine, sums[j], sum_term);
            }
        }
    }
    constexpr int vectors = (2 * K + 7) / 8 * 8; // weights, then sums, padded to whole rounds of lane_sums
    __m512i all[vectors];
    for (int v = 0; v < vectors; ++v) all[v] = v < K ? weights[v] : v < 2 * K ? sums[v - K] : _mm512_setzero_si512();
    alignas(64) std::int64_t totals[vectors];
    for (int v = 0; v < vectors; v += 8) _mm512_store_si512(totals + v, lane_sums(all + v));
    std::int64_t weight_unit = 1;
    if constexpr (OneOpticalDepth) {
        const double units = double(first_optical) * cluster_fixed_scale;
        if (!(std::abs(units) < 0x1p51)) return false;
        weight_unit = std::int64_t(units); // fixed_sum(b), which every fragment taken would add
    }
    for (int j = 0; j < K; ++j) {
        weight[j] = std::int64_t(std::uint64_t(weight_unit) * std::uint64_t(totals[j])); // wraps as the sum of the terms would
        sum[j] = totals[K + j];
    }
    return too_large == 0;
}

/// clustered::texel_assigner for sixteen depths: the first `filled` bin [lo, hi) holding the depth
/// (or equal to a bin of no width), else the nearest usable mean.
template <int K>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512i bins_of(__m512 depth, const float* lo, const float* hi, std::uint32_t filled,
                                                                          const float* means, std::uint32_t usable) noexcept {
    __m512i layer = nearest_centre<K>(depth, means, usable);
    for (int j = K - 1; j >= 0; --j) { // the first bin holding the depth is the last to write
        if (!(filled >> j & 1u)) continue;
        const __m512 low = _mm512_set1_ps(lo[j]);
        __mmask16 inside = _mm512_cmp_ps_mask(depth, _mm512_set1_ps(hi[j]), _CMP_LT_OQ);
        if (lo[j] == hi[j]) inside |= _mm512_cmp_ps_mask(depth, low, _CMP_EQ_OQ);
        inside &= _mm512_cmp_ps_mask(depth, low, _CMP_GE_OQ);
        layer = _mm512_mask_mov_epi32(layer, inside, _mm512_set1_epi32(j));
    }
    return layer;
}

/// layers[i] = bins_of(fragments[i].depth) for every fragment.
template <int K, texel_fragment Fragment>
HAIRSHADOW_AVX512_TARGET inline void assign_to_bins(std::span<const Fragment> fragments, const float* lo, const float* hi, std::uint32_t filled,
                                                    const float* means, std::uint32_t usable, std::int32_t* layers) noexcept {
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        _mm512_mask_storeu_epi32(layers + i, lanes, bins_of<K>(depth, lo, hi, filled, means, usable));
    }
}

/// counts[j] += the fragments whose bins_of is j: assign_to_bins's layers, counted by their masks.
template <int K, texel_fragment Fragment>
HAIRSHADOW_AVX512_TARGET inline void count_in_bins(std::span<const Fragment> fragments, const float* lo, const float* hi, std::uint32_t filled,
                                                   const float* means, std::uint32_t usable, std::uint32_t* counts) noexcept {
    for (std::size_t i = 0; i < fragments.size(); i += 16) {
        __m512 depth, optical;
        const __mmask16 lanes = load_fragments(fragments.data() + i, fragments.size() - i, depth, optical);
        const __m512i layer = bins_of<K>(depth, lo, hi, filled, means, usable);
        for (int j = 0; j < K; ++j)
            counts[j] += std::uint32_t(std::popcount(unsigned(_mm512_mask_cmpeq_epi32_mask(lanes, layer, _mm512_set1_epi32(j)))));
    }
}

} // namespace avx512
#endif

} // namespace hairshadow::detail
