#pragma once
/// @file
/// A placement's per-fragment steps, sixteen fragments at a time where the placement offers it:
/// - assign_each: the layers of fragments from many texels (the streamed build, methods/detail/streamed_tile.hpp),
///   through a placement's assign_each_avx512;
/// - prepare_texel and for_each_layer: one texel's pre-pass and layers (the grouped build), through
///   prepare_texel_avx512 and assign_texel_avx512 (or, for a texel's depths alone,
///   prepare_texel_depths_avx512: builds_from_depths_avx512).
/// The vector forms give the scalar results bit for bit: the same IEEE subtraction, division and
/// comparisons in every lane, so that only the instruction count changes. Which runs follows
/// raster_options::instructions (raster/instruction_set.hpp).

#include <hairshadow/placement/layer_position.hpp>
#include <hairshadow/policies/capabilities.hpp>
#include <hairshadow/raster/instruction_set.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

namespace hairshadow::detail {

#if HAIRSHADOW_AVX512_WALK
namespace avx512 {
/// The first `remaining` of sixteen lanes (all of them from 16 on).
inline __mmask16 first_lanes(std::size_t remaining) noexcept {
    return remaining >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << remaining) - 1u);
}

/// Per lane, how many of boundaries[0..Count) x has reached (x >= b), as the placements' scalar
/// assign counts them: none for NaN.
template <int Count>
HAIRSHADOW_AVX512_TARGET inline __m512i boundaries_reached(__m512 x, const float* boundaries) noexcept {
    const __m512i one = _mm512_set1_epi32(1);
    __m512i reached = _mm512_setzero_si512();
    for (int i = 0; i < Count; ++i)
        reached = _mm512_mask_add_epi32(reached, _mm512_cmp_ps_mask(x, _mm512_set1_ps(boundaries[i]), _CMP_GE_OQ), reached, one);
    return reached;
}

/// settle_layer (placement/layer_position.hpp) in the `lanes` of k: each lane's estimate moved down
/// while k > 0 and x < boundary(k), then up while k < last and x >= boundary(k + 1), one step at a
/// time while any lane still moves. boundary(k, movable) gives boundary k of each movable lane.
template <class Boundary>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512i settle_layers(__m512i k, __m512 x, __mmask16 lanes, int last,
                                                                             Boundary&& boundary) noexcept {
    const __m512i one = _mm512_set1_epi32(1);
    for (;;) {
        const __mmask16 movable = _mm512_mask_cmpgt_epi32_mask(lanes, k, _mm512_setzero_si512());
        const __mmask16 down = _mm512_mask_cmp_ps_mask(movable, x, boundary(k, movable), _CMP_LT_OQ);
        if (!down) break;
        k = _mm512_mask_sub_epi32(k, down, k, one);
    }
    for (;;) {
        const __m512i next = _mm512_add_epi32(k, one);
        const __mmask16 movable = _mm512_mask_cmplt_epi32_mask(lanes, k, _mm512_set1_epi32(last));
        const __mmask16 up = _mm512_mask_cmp_ps_mask(movable, x, boundary(next, movable), _CMP_GE_OQ);
        if (!up) break;
        k = _mm512_mask_mov_epi32(k, up, next);
    }
    return k;
}
} // namespace avx512
#endif

/// layers[i] = placement.assign(states[texels[i]], depths[i]) for every fragment i, sixteen at a time
/// where the placement can and `instructions` (resolved) is avx512.
template <class Placement>
void assign_each(const Placement& placement, std::span<const typename Placement::texel_state> states, std::span<const std::uint32_t> texels,
                 std::span<const float> depths, std::span<std::int32_t> layers, instruction_set instructions) noexcept {
#if HAIRSHADOW_AVX512_WALK
    if constexpr (assigns_each_avx512<Placement>)
        if (instructions == instruction_set::avx512) return placement.assign_each_avx512(states.data(), texels, depths, layers.data());
#endif
    (void)instructions;
    for (std::size_t i = 0; i < texels.size(); ++i) layers[i] = placement.assign(states[texels[i]], depths[i]);
}

/// placement.prepare_texel(fragments, state), sixteen fragments at a time where the placement can and
/// `instructions` (resolved) is avx512.
template <class Placement, class Fragment>
void prepare_texel(const Placement& placement, std::span<const Fragment> fragments, typename Placement::texel_state& state,
                   instruction_set instructions) noexcept {
#if HAIRSHADOW_AVX512_WALK
    if constexpr (std::is_same_v<Fragment, optical_fragment> && prepares_texel_avx512<Placement>)
        if (instructions == instruction_set::avx512) return placement.prepare_texel_avx512(fragments, state);
#endif
    (void)instructions;
    placement.prepare_texel(fragments, state);
}

/// Calls visit(layer, fragment) for each of a texel's fragments in order, with layer =
/// placement.assign(state, fragment.depth): sixteen at a time where the placement can and
/// `instructions` (resolved) is avx512, else through texel_assigner.
template <class Placement, class Fragment, class Visit>
HAIRSHADOW_ALWAYS_INLINE inline void for_each_layer(const Placement& placement, const typename Placement::texel_state& state,
                                             std::span<const Fragment> fragments, instruction_set instructions, Visit&& visit) {
#if HAIRSHADOW_AVX512_WALK
    if constexpr (std::is_same_v<Fragment, optical_fragment> && assigns_texel_avx512<Placement>) {
        if (instructions == instruction_set::avx512) {
            constexpr std::size_t block = 64; // a block's layers stay in registers and the first-level cache
            std::array<std::int32_t, block> layers;
            for (std::size_t first = 0; first < fragments.size(); first += block) {
                const auto part = fragments.subspan(first, std::min(block, fragments.size() - first));
                placement.assign_texel_avx512(state, part, layers.data());
                for (std::size_t i = 0; i < part.size(); ++i) visit(int(layers[i]), part[i]);
            }
            return;
        }
    }
#endif
    (void)instructions;
    const auto assign = texel_assigner(placement, state);
    for (const auto& f : fragments) visit(assign(f.depth), f);
}

/// counts[k] += the fragments of layers[0..n) in layer k. Layers are in [-1, L), as placements assign
/// them; -1 (no layer) counts nowhere. With few layers, one pass per layer (comparisons that
/// vectorise); with many, one increment per fragment.
template <std::size_t L>
HAIRSHADOW_ALWAYS_INLINE inline void add_layer_counts(const std::int32_t* layers, std::size_t n, std::array<std::uint32_t, L>& counts) noexcept {
    if constexpr (L <= 16) {
        for (std::size_t j = 0; j < L; ++j) {
            std::uint32_t c = 0;
            for (std::size_t i = 0; i < n; ++i) c += std::uint32_t(layers[i] == std::int32_t(j));
            counts[j] += c;
        }
    } else {
        for (std::size_t i = 0; i < n; ++i)
            if (layers[i] >= 0) ++counts[std::size_t(layers[i])];
    }
}

/// How many of a texel's fragments fall in each layer (placement.assign): sixteen at a time where the
/// placement counts in vectors (count_texel_avx512) and `instructions` (resolved) is avx512.
template <class Placement, class Fragment, std::size_t L = std::size_t(Placement::layer_count)>
HAIRSHADOW_ALWAYS_INLINE inline std::array<std::uint32_t, L> layer_counts(const Placement& placement, const typename Placement::texel_state& state,
                                                                     std::span<const Fragment> fragments, instruction_set instructions) {
    std::array<std::uint32_t, L> counts{};
    constexpr std::size_t block = 64;
    std::array<std::int32_t, block> layers;
#if HAIRSHADOW_AVX512_WALK
    if constexpr (std::is_same_v<Fragment, optical_fragment> && counts_texel_avx512<Placement>) {
        if (instructions == instruction_set::avx512) {
            placement.count_texel_avx512(state, fragments, counts);
            return counts;
        }
    }
#endif
    (void)instructions;
    const auto assign = texel_assigner(placement, state);
    for (std::size_t first = 0; first < fragments.size(); first += block) {
        const std::size_t n = std::min(block, fragments.size() - first);
        for (std::size_t i = 0; i < n; ++i) layers[i] = std::int32_t(assign(fragments[first + i].depth));
        add_layer_counts(layers.data(), n, counts);
    }
    return counts;
}

} // namespace hairshadow::detail
