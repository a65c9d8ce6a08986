#pragma once
/// @file
/// The placements' layers sixteen fragments at a time, in AVX-512F: each function is one placement's
/// assign() for fragments of many texels (layers[i] = assign(states[texels[i]], depths[i])), behind
/// its assign_each_avx512 member (the capability assigns_each_avx512, policies/capabilities.hpp). The
/// same IEEE subtraction, division and comparisons in every lane as the scalar assign, and the
/// estimates settled against the same boundaries, so every layer is assign's, bit for bit
/// (tests/test_placement_steps.cpp). Each is inlined into its member, as it was when it was the
/// member's body (measured with and without: no difference, BENCHMARKS.md, "Issue 40").

#include <hairshadow/placement/detail/assign_each.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>

#if HAIRSHADOW_AVX512_WALK
namespace hairshadow::detail::avx512 {

/// planar_slices<N>::assign, N <= 16: the comparisons with D_1..D_N lane by lane (`boundaries` holds
/// D_0..D_N).
template <int N>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline void assign_planar_by_count(const float* boundaries, std::span<const std::uint32_t> texels, std::span<const float> depths,
                                                     std::int32_t* layers) noexcept {
    for (std::size_t i = 0; i < texels.size(); i += 16) {
        const __mmask16 lanes = first_lanes(texels.size() - i);
        const __m512i reached = boundaries_reached<N>(_mm512_maskz_loadu_ps(lanes, depths.data() + i), boundaries + 1);
        _mm512_mask_storeu_epi32(layers + i, lanes, _mm512_min_epi32(reached, _mm512_set1_epi32(N - 1)));
    }
}

/// planar_slices<N>::assign for 17 to 64 maps, by bisection in registers: assign's min(reached, N - 1)
/// is the number of D_1..D_{N-1} at or below the depth, and since they never decrease, six halvings
/// of a table of them (padded with NaN, which no depth reaches) find it, as reached's upper_bound
/// does. A NaN depth reaches none, as in reached.
template <int N>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline void assign_planar_by_bisection(const float* boundaries, std::span<const std::uint32_t> texels, std::span<const float> depths,
                                                         std::int32_t* layers) noexcept {
    static_assert(N > 16 && N <= 64);
    alignas(64) float table[64];
    std::fill(std::begin(table), std::end(table), std::numeric_limits<float>::quiet_NaN());
    std::copy(boundaries + 1, boundaries + N, table); // D_1 .. D_{N-1}
    const __m512 t0 = _mm512_load_ps(table), t1 = _mm512_load_ps(table + 16), t2 = _mm512_load_ps(table + 32), t3 = _mm512_load_ps(table + 48);
    for (std::size_t i = 0; i < texels.size(); i += 16) {
        const __mmask16 lanes = first_lanes(texels.size() - i);
        const __m512 depth = _mm512_maskz_loadu_ps(lanes, depths.data() + i);
        __m512i below = _mm512_setzero_si512(); // table entries known to be at or below the depth
        for (int step = 32; step >= 1; step /= 2) {
            const __m512i probe = _mm512_add_epi32(below, _mm512_set1_epi32(step - 1));
            const __m512 low_half = _mm512_permutex2var_ps(t0, probe, t1), high_half = _mm512_permutex2var_ps(t2, probe, t3);
            const __m512 entry = _mm512_mask_blend_ps(_mm512_test_epi32_mask(probe, _mm512_set1_epi32(32)), low_half, high_half);
            below = _mm512_mask_add_epi32(below, _mm512_cmp_ps_mask(entry, depth, _CMP_LE_OQ), below, _mm512_set1_epi32(step));
        }
        _mm512_mask_storeu_epi32(layers + i, lanes, below);
    }
}

/// per_pixel_depth's locate estimate settled against its relative boundaries d_0..d_K, for K > 8:
/// the boundaries reached, K beyond the last (rel >= 1), 0 in front and for NaN.
template <int K, bool Linear>
HAIRSHADOW_AVX512_TARGET __m512i settled_per_pixel_layer(__m512 rel, __mmask16 lanes, const float* d) noexcept {
    const __m512 last = _mm512_set1_ps(float(K - 1));
    const __mmask16 inside = _mm512_mask_cmp_ps_mask(_mm512_mask_cmp_ps_mask(lanes, rel, _mm512_setzero_ps(), _CMP_GE_OQ), rel,
                                                     _mm512_set1_ps(1.0f), _CMP_LT_OQ);
    __m512 estimate;
    if constexpr (Linear) {
        const __m512 root = _mm512_sqrt_ps(_mm512_add_ps(_mm512_set1_ps(1.0f), _mm512_mul_ps(rel, _mm512_set1_ps(4.0f * float(K * (K + 1))))));
        estimate = _mm512_mul_ps(_mm512_sub_ps(root, _mm512_set1_ps(1.0f)), _mm512_set1_ps(0.5f));
    } else {
        estimate = _mm512_mul_ps(rel, _mm512_set1_ps(float(K)));
    }
    const __mmask16 positive = _mm512_mask_cmp_ps_mask(inside, estimate, _mm512_setzero_ps(), _CMP_GT_OQ);
    __m512i k = _mm512_maskz_cvttps_epi32(positive, _mm512_min_ps(estimate, last));
    k = settle_layers(k, rel, inside, K - 1, [=](__m512i j, __mmask16 movable) HAIRSHADOW_AVX512_TARGET {
        return _mm512_mask_i32gather_ps(rel, movable, j, d, 4);
    });
    const __mmask16 beyond = _mm512_mask_cmp_ps_mask(lanes, rel, _mm512_set1_ps(1.0f), _CMP_GE_OQ);
    return _mm512_mask_mov_epi32(_mm512_maskz_mov_epi32(inside, k), beyond, _mm512_set1_epi32(K));
}

/// per_pixel_depth<K>::assign: z0 (and, where the last layer extends, the stretch after it) gathered
/// from the texels' states, the same subtraction and division lane by lane, then assign's boundary
/// count (K <= 8) or locate's estimate settled against the same boundaries. The settled layer does
/// not depend on the estimate, only on the boundaries, so the estimate need not match locate's to the
/// bit. `Ignore`: a depth beyond the last layer is dropped (-1), else it joins the last layer.
template <int K, bool Linear, bool Extend, bool Ignore, class State>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline void assign_per_pixel(const State* states, float extent, const float* relative_boundaries, std::span<const std::uint32_t> texels,
                                               std::span<const float> depths, std::int32_t* layers) noexcept {
    constexpr int stride = int(sizeof(State)); // the gathers' scale: 4 or 8 bytes a texel
    const float* z0s = reinterpret_cast<const float*>(states);
    const __m512 extent_v = _mm512_set1_ps(extent);
    for (std::size_t i = 0; i < texels.size(); i += 16) {
        const __mmask16 lanes = first_lanes(texels.size() - i);
        const __m512i texel = _mm512_maskz_loadu_epi32(lanes, texels.data() + i);
        const __m512 depth = _mm512_maskz_loadu_ps(lanes, depths.data() + i);
        const __m512 z0 = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, texel, z0s, stride);
        __m512 span = extent_v;
        if constexpr (Extend) span = _mm512_mul_ps(extent_v, _mm512_mask_i32gather_ps(_mm512_set1_ps(1.0f), lanes, texel, z0s + 1, stride));
        const __m512 rel = _mm512_div_ps(_mm512_sub_ps(depth, z0), span);
        __m512i layer; // the boundaries d_1..d_K reached: K beyond the last layer, 0 in front and for NaN
        if constexpr (K <= 8) layer = boundaries_reached<K>(rel, relative_boundaries + 1);
        else layer = settled_per_pixel_layer<K, Linear>(rel, lanes, relative_boundaries);
        if constexpr (Ignore) layer = _mm512_mask_set1_epi32(layer, _mm512_cmpeq_epi32_mask(layer, _mm512_set1_epi32(K)), -1);
        else layer = _mm512_min_epi32(layer, _mm512_set1_epi32(K - 1));
        _mm512_mask_storeu_epi32(layers + i, lanes, layer);
    }
}

/// depth_range<S>'s boundary k between nearest and nearest + span, as boundary() rounds it.
template <int S>
HAIRSHADOW_AVX512_TARGET __m512 depth_range_boundary(__m512 nearest, __m512 span, __m512i k) noexcept {
    const __m512 fraction = _mm512_div_ps(_mm512_cvtepi32_ps(k), _mm512_set1_ps(float(S)));
    return _mm512_add_ps(nearest, rounded(_mm512_mul_ps(span, fraction)));
}

/// depth_range<S>::assign: the same estimate, settled against the same boundaries, lane by lane, one
/// step at a time while any lane still moves. `states` are {nearest, furthest} pairs of floats.
template <int S>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline void assign_depth_range(const float* ranges, std::span<const std::uint32_t> texels, std::span<const float> depths,
                                                 std::int32_t* layers) noexcept {
    const __m512 slices = _mm512_set1_ps(float(S));
    for (std::size_t i = 0; i < texels.size(); i += 16) {
        const __mmask16 lanes = first_lanes(texels.size() - i);
        const __m512i texel = _mm512_maskz_loadu_epi32(lanes, texels.data() + i);
        const __m512 depth = _mm512_maskz_loadu_ps(lanes, depths.data() + i);
        const __m512 nearest = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, texel, ranges, 8);
        const __m512 furthest = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, texel, ranges + 1, 8);
        const __m512 span = _mm512_sub_ps(furthest, nearest);
        const __mmask16 ranged = _mm512_mask_cmp_ps_mask(lanes, furthest, nearest, _CMP_GT_OQ); // else slice 0
        // settle_layer: the estimate's whole part (0 for NaN and negatives), then down and up.
        const __m512 estimate = _mm512_mul_ps(_mm512_div_ps(_mm512_sub_ps(depth, nearest), span), slices);
        const __mmask16 positive = _mm512_mask_cmp_ps_mask(ranged, estimate, _mm512_setzero_ps(), _CMP_GT_OQ);
        __m512i k = _mm512_maskz_cvttps_epi32(positive, _mm512_min_ps(estimate, slices));
        k = settle_layers(k, depth, ranged, S, [=](__m512i j, __mmask16) HAIRSHADOW_AVX512_TARGET {
            return depth_range_boundary<S>(nearest, span, j);
        });
        k = _mm512_min_epi32(k, _mm512_set1_epi32(S - 1)); // never negative: it starts at 0 or above and stops there
        _mm512_mask_storeu_epi32(layers + i, lanes, k);
    }
}

} // namespace hairshadow::detail::avx512
#endif
