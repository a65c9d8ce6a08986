#pragma once
/// @file
/// A placement's layer for each of many fragments: the streamed build's per-fragment step
/// (methods/streamed_tile.hpp). A placement may offer assign_each_avx512, which gives assign()'s
/// layers bit for bit sixteen fragments at a time: the same IEEE subtraction, division and
/// comparisons in every lane, so that only the instruction count changes. The rest are assigned one
/// at a time. Which runs follows raster_options::instructions (raster/instruction_set.hpp).

#include <hairshadow/raster/instruction_set.hpp>

#include <cstddef>
#include <cstdint>
#include <span>

namespace hairshadow::detail {

#if HAIRSHADOW_AVX512_WALK
/// Whether `Placement` assigns sixteen fragments at a time.
template <class Placement>
concept assigns_each_avx512 = requires(const Placement& p, const typename Placement::texel_state* states, std::span<const std::uint32_t> texels,
                                       std::span<const float> depths, std::int32_t* layers) {
    p.assign_each_avx512(states, texels, depths, layers);
};

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

} // namespace hairshadow::detail
