#pragma once
/// @file
/// The steps of the line walk in a tile, sixteen segments at a time (AVX-512F): which texel centres
/// along its major axis each segment crosses, and how many of them lie in the tile. The walk sets
/// its segments up with it (raster/detail/tile_walk_lanes_avx512.hpp), and the projection counts
/// with it each segment's steps in the tiles it lands in (raster/detail/segment_project_avx512.hpp),
/// the key by which the walk in any order sorts a tile's segments.

#include <hairshadow/raster/instruction_set.hpp>
#include <hairshadow/raster/line_rule.hpp>

#include <cstdint>

#if HAIRSHADOW_AVX512_WALK
namespace hairshadow::detail::avx512 {

/// floor(x / 2^bits) per lane: an arithmetic shift floors negative values too.
HAIRSHADOW_AVX512_TARGET inline __m512i texel_of(__m512i x) noexcept { return _mm512_srai_epi32(x, HAIRSHADOW_SUBPIXEL_BITS); }

/// The texel centres along the major axis that sixteen segments, ends (ax, ay) and (bx, by) in
/// sub-pixels relative to a tile of w x h texels (per lane), cross: all of them (first to last), and
/// those in the tile (count of them from m_begin, in [0, max(w, h)] whatever the ends): the walk's steps.
struct major_steps {
    __mmask16 x_major, rising;
    __m512i first, last, m_begin, count;

    HAIRSHADOW_AVX512_TARGET major_steps(__m512i ax, __m512i ay, __m512i bx, __m512i by, __m512i w, __m512i h) noexcept {
        const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1);
        const __m512i dx = _mm512_sub_epi32(bx, ax), dy = _mm512_sub_epi32(by, ay);
        x_major = _mm512_cmpge_epi32_mask(_mm512_abs_epi32(dx), _mm512_abs_epi32(dy));
        const __m512i major_a = _mm512_mask_blend_epi32(x_major, ay, ax), major_b = _mm512_mask_blend_epi32(x_major, by, bx);
        rising = _mm512_cmpgt_epi32_mask(_mm512_mask_blend_epi32(x_major, dy, dx), zero);
        const __m512i lo_end = _mm512_mask_blend_epi32(rising, major_b, major_a), hi_end = _mm512_mask_blend_epi32(rising, major_a, major_b);
        // Centres c S + H crossed: first = ceil((lo - H) / S), last = ceil((hi - H) / S) - 1.
        const __m512i round_up = _mm512_set1_epi32(std::int32_t(subpixel_scale - 1 - subpixel_scale / 2));
        first = texel_of(_mm512_add_epi32(lo_end, round_up));
        last = _mm512_sub_epi32(texel_of(_mm512_add_epi32(hi_end, round_up)), one);
        const __m512i extent = _mm512_mask_blend_epi32(x_major, h, w);
        m_begin = _mm512_max_epi32(first, zero);
        const __m512i m_end = _mm512_min_epi32(last, _mm512_sub_epi32(extent, one));
        count = _mm512_max_epi32(_mm512_add_epi32(_mm512_sub_epi32(m_end, m_begin), one), zero);
    }
    /// For one tile of w x h texels.
    HAIRSHADOW_AVX512_TARGET major_steps(__m512i ax, __m512i ay, __m512i bx, __m512i by, int w, int h) noexcept
        : major_steps(ax, ay, bx, by, _mm512_set1_epi32(w), _mm512_set1_epi32(h)) {}
};

/// The walk's steps (major_steps::count) of sixteen segments, ends in the map's sub-pixels (within
/// the guard band), each in its tile (tx, ty) of a map of `res` texels in tiles of 2^tile_shift:
/// the same count as major_steps in the tile's own coordinates, since a tile's corner is a whole
/// texel and texel_of shifts exactly by it.
HAIRSHADOW_AVX512_TARGET inline __m512i steps_in_tile(__m512i ax, __m512i ay, __m512i bx, __m512i by, __m512i tx, __m512i ty, int tile_shift,
                                                     int res) noexcept {
    const __m512i x0 = _mm512_slli_epi32(tx, tile_shift), y0 = _mm512_slli_epi32(ty, tile_shift);
    const __m512i ox = _mm512_slli_epi32(x0, HAIRSHADOW_SUBPIXEL_BITS), oy = _mm512_slli_epi32(y0, HAIRSHADOW_SUBPIXEL_BITS);
    const __m512i side = _mm512_set1_epi32(1 << tile_shift), map = _mm512_set1_epi32(res);
    const __m512i w = _mm512_min_epi32(side, _mm512_sub_epi32(map, x0)), h = _mm512_min_epi32(side, _mm512_sub_epi32(map, y0));
    return major_steps(_mm512_sub_epi32(ax, ox), _mm512_sub_epi32(ay, oy), _mm512_sub_epi32(bx, ox), _mm512_sub_epi32(by, oy), w, h).count;
}

} // namespace hairshadow::detail::avx512
#endif
