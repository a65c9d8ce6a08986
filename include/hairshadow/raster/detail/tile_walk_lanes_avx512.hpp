#pragma once
/// @file
/// The kernels of the tiled build's line walk in AVX-512F (raster/detail/tile_walk_avx512.hpp walks a tile
/// with them), chosen at run time (raster_options::instructions). Sixteen
/// segments of a tile are gathered and set up at once, one per lane: major axis, the texel centres they cross in
/// the tile, the exact quotient and remainder of the minor coordinate, the end's diamond and the start
/// fragment (the diamond-exit rule of line_rule.hpp, without a branch). Segments of at most sixteen
/// texels in the tile are then walked in lockstep, one step of all sixteen at a time, the minor
/// coordinate carried from step to step as an exact quotient and remainder, each start fragment put in
/// the step after its segment's last; a register transpose turns the steps into each segment's
/// fragments. Longer segments are walked one at a time, sixteen texels
/// per step. Either way the fragments are compressed into the tile's store segment after segment, so
/// that segment order, and every sum, is the scalar walk's. Every quantity is an integer, or an
/// integer held exactly in a double, until the depth: that is a + (b - a) t, t in float, rounded as
/// the scalar walk rounds them. Where the build allows any order (fragment_order::any), every batch
/// walks in lockstep, each step's fragments stored as they come (no transpose), the tile's segments in
/// list order, or sorted by their steps in the tile where their lengths spread so far that list order
/// would leave many lanes idle.

#include <hairshadow/raster/instruction_set.hpp>
#include <hairshadow/raster/line_rule.hpp>
#include <hairshadow/raster/detail/segment_bins.hpp>

#include <algorithm>
#include <cstdint>
#include <span>

namespace hairshadow::detail::avx512 {

/// inside_diamond (line_rule.hpp) for sixteen points and texels.
HAIRSHADOW_AVX512_TARGET inline __mmask16 inside_diamond(__m512i px, __m512i py, __m512i c, __m512i r) noexcept {
    const __m512i half = _mm512_set1_epi32(std::int32_t(subpixel_scale / 2));
    const __m512i u = _mm512_sub_epi32(px, _mm512_add_epi32(_mm512_slli_epi32(c, HAIRSHADOW_SUBPIXEL_BITS), half));
    const __m512i v = _mm512_sub_epi32(py, _mm512_add_epi32(_mm512_slli_epi32(r, HAIRSHADOW_SUBPIXEL_BITS), half));
    const __m512i l1 = _mm512_add_epi32(_mm512_abs_epi32(u), _mm512_abs_epi32(v));
    return __mmask16(_mm512_cmplt_epi32_mask(l1, half) | (_mm512_cmpeq_epi32_mask(l1, half) & _mm512_cmpgt_epi32_mask(u, _mm512_setzero_si512())));
}

/// floor(x / 2^bits) per lane: an arithmetic shift floors negative values too.
HAIRSHADOW_AVX512_TARGET inline __m512i texel_of(__m512i x) noexcept { return _mm512_srai_epi32(x, HAIRSHADOW_SUBPIXEL_BITS); }

/// q = floor(num / denom) and the remainder num - q denom, for integers num and denom > 0 held exactly
/// in doubles (|num| < 2^52). The product with 1 / denom misses the quotient by far less than one, so
/// one correction each way makes it exact, with no division.
HAIRSHADOW_AVX512_TARGET inline void exact_quotient(__m512d num, __m512d denom, __m512d inv_denom, __m512d& q, __m512d& rem) noexcept {
    q = _mm512_roundscale_pd(_mm512_mul_pd(num, inv_denom), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    rem = _mm512_sub_pd(num, _mm512_mul_pd(q, denom)); // exact: integers below 2^53
    const __mmask8 below = _mm512_cmp_pd_mask(rem, _mm512_setzero_pd(), _CMP_LT_OQ);
    q = _mm512_mask_sub_pd(q, below, q, _mm512_set1_pd(1.0));
    rem = _mm512_mask_add_pd(rem, below, rem, denom);
    const __mmask8 above = _mm512_cmp_pd_mask(rem, denom, _CMP_GE_OQ);
    q = _mm512_mask_add_pd(q, above, q, _mm512_set1_pd(1.0));
    rem = _mm512_mask_sub_pd(rem, above, rem, denom);
}

/// Lane halves as doubles.
HAIRSHADOW_AVX512_TARGET inline __m512d low_pd(__m512i x) noexcept { return _mm512_cvtepi32_pd(_mm512_castsi512_si256(x)); }
HAIRSHADOW_AVX512_TARGET inline __m512d high_pd(__m512i x) noexcept { return _mm512_cvtepi32_pd(_mm512_extracti64x4_epi64(x, 1)); }
HAIRSHADOW_AVX512_TARGET inline __m512i join_epi32(__m256i low, __m256i high) noexcept {
    return _mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1);
}

/// The depth along sixteen segments (or one, broadcast) at texel centres: segment_shader::parameter,
/// t = ((x S + H - ax) dx + (y S + H - ay) dy) / |d|^2 clamped to [0, 1] in float, each product
/// rounded on its own, then lerp_exact, rounded as the scalar walk rounds them. (max returns its
/// second operand on equal zeros, so -0 clamps to +0 as the scalar comparison does.)
struct depth_along {
    __m512i ax, ay;
    __m512 dx, dy, inv_length2;
    __m512 depth_a, depth_delta;

    HAIRSHADOW_AVX512_TARGET __m512 at(__m512i x, __m512i y) const noexcept {
        constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
        const __m512i half = _mm512_set1_epi32(std::int32_t(subpixel_scale / 2));
        const __m512 px = _mm512_cvtepi32_ps(_mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(x, bits), half), ax));
        const __m512 py = _mm512_cvtepi32_ps(_mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(y, bits), half), ay));
        const __m512 dot = rounded(_mm512_add_ps(rounded(_mm512_mul_ps(px, dx)), rounded(_mm512_mul_ps(py, dy))));
        const __m512 param = _mm512_max_ps(_mm512_min_ps(_mm512_mul_ps(dot, inv_length2), _mm512_set1_ps(1.0f)), _mm512_setzero_ps());
        return _mm512_add_ps(depth_a, rounded(_mm512_mul_ps(depth_delta, param))); // lerp_exact
    }
};

/// floor(num / denom) along a walk, per lane, as quotient and remainder (0 <= r < denom): each
/// advance() adds num's step, held as its own quotient and remainder, with a carry. Exact integers:
/// r + r_step < 2 denom < 2^32 (denom < 2^31: most_length), compared unsigned, so that no step divides.
struct carried_quotient {
    __m512i q, r, q_step, r_step, denom;

    /// The minor texel of the line rule: the quotient, one less on an exact tie where `tie` says so.
    HAIRSHADOW_AVX512_TARGET __m512i minor(__mmask16 tie) const noexcept {
        const __mmask16 on_tie = _mm512_cmpeq_epi32_mask(r, _mm512_setzero_si512());
        return _mm512_mask_sub_epi32(q, __mmask16(on_tie & tie), q, _mm512_set1_epi32(1));
    }
    HAIRSHADOW_AVX512_TARGET void advance() noexcept {
        q = _mm512_add_epi32(q, q_step);
        r = _mm512_add_epi32(r, r_step);
        const __mmask16 carry = _mm512_cmpge_epu32_mask(r, denom);
        q = _mm512_mask_add_epi32(q, carry, q, _mm512_set1_epi32(1));
        r = _mm512_mask_sub_epi32(r, carry, r, denom);
    }
};

/// The texels of sixteen walk steps in the tile, each lane's at major coordinate m: the row-major
/// index where the step makes a fragment (in the tile, not the end's diamond, `active`), else `none`;
/// x and y are the texel's coordinates.
HAIRSHADOW_AVX512_TARGET inline __m512i step_texels(__m512i m, __m512i minor, __mmask16 active, __mmask16 along_x, __m512i end_major,
                                                   __m512i end_minor, __m512i minor_extent, __m512i width, __m512i none, __m512i& x,
                                                   __m512i& y) noexcept {
    const __mmask16 at_end = _mm512_cmpeq_epi32_mask(m, end_major) & _mm512_cmpeq_epi32_mask(minor, end_minor);
    const __mmask16 keep = active & _mm512_cmplt_epu32_mask(minor, minor_extent) & __mmask16(~at_end);
    x = _mm512_mask_blend_epi32(along_x, minor, m), y = _mm512_mask_blend_epi32(along_x, m, minor);
    return _mm512_mask_add_epi32(none, keep, _mm512_mullo_epi32(y, width), x);
}

/// Sixteen integers held in two halves of doubles, as int32.
HAIRSHADOW_AVX512_TARGET inline __m512i integers_of(__m512d low, __m512d high) noexcept {
    return join_epi32(_mm512_cvttpd_epi32(low), _mm512_cvttpd_epi32(high));
}

/// The texel centres along the major axis that sixteen segments, ends (ax, ay) and (bx, by) in
/// sub-pixels relative to a tile of w x h texels, cross: all of them (first to last), and those in
/// the tile (count of them from m_begin): the walk's steps.
struct major_steps {
    __mmask16 x_major, rising;
    __m512i first, last, m_begin, count;

    HAIRSHADOW_AVX512_TARGET major_steps(__m512i ax, __m512i ay, __m512i bx, __m512i by, int w, int h) noexcept {
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
        const __m512i extent = _mm512_mask_blend_epi32(x_major, _mm512_set1_epi32(h), _mm512_set1_epi32(w));
        m_begin = _mm512_max_epi32(first, zero);
        const __m512i m_end = _mm512_min_epi32(last, _mm512_sub_epi32(extent, one));
        count = _mm512_max_epi32(_mm512_add_epi32(_mm512_sub_epi32(m_end, m_begin), one), zero);
    }
};

/// Sixteen segments set up for the walk, in tile-relative coordinates (sub-pixels for ends, texels
/// for the rest). Lanes not `simd` are walked in scalar.
struct alignas(64) batch {
    std::int32_t ax[16], ay[16], bx[16], by[16];
    std::int32_t m_begin[16], count[16], end_major[16], end_minor[16], minor_extent[16], start_x[16], start_y[16];
    double num0[16], step[16], denom[16], inv_denom[16];
    float inv_length2[16];
    float start_depth[16];
    float depth_a[16], depth_delta[16];
    std::uint16_t x_major, tie, start, simd;

    /// The depth along the sixteen segments.
    HAIRSHADOW_AVX512_TARGET depth_along depths() const noexcept {
        const __m512i a_x = _mm512_load_si512(ax), a_y = _mm512_load_si512(ay);
        const __m512i dx = _mm512_sub_epi32(_mm512_load_si512(bx), a_x), dy = _mm512_sub_epi32(_mm512_load_si512(by), a_y);
        return {a_x, a_y, _mm512_cvtepi32_ps(dx), _mm512_cvtepi32_ps(dy), _mm512_load_ps(inv_length2), _mm512_load_ps(depth_a), _mm512_load_ps(depth_delta)};
    }
    /// The depth along lane l's segment, in every lane.
    HAIRSHADOW_AVX512_TARGET depth_along depths(int l) const noexcept {
        return {_mm512_set1_epi32(ax[l]),
                _mm512_set1_epi32(ay[l]),
                _mm512_set1_ps(float(bx[l] - ax[l])),
                _mm512_set1_ps(float(by[l] - ay[l])),
                _mm512_set1_ps(inv_length2[l]),
                _mm512_set1_ps(depth_a[l]),
                _mm512_set1_ps(depth_delta[l])};
    }
};

/// Vector set-up of the sixteen segments in b.ax..b.by for a tile of w x h texels: walk_line's
/// quantities, lane by lane.
HAIRSHADOW_AVX512_TARGET inline void set_up(batch& b, int w, int h) noexcept {
    constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
    const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1);
    const __m512i half = _mm512_set1_epi32(std::int32_t(subpixel_scale / 2));
    const __m512i ax = _mm512_load_si512(b.ax), ay = _mm512_load_si512(b.ay), bx = _mm512_load_si512(b.bx), by = _mm512_load_si512(b.by);
    const __m512i dx = _mm512_sub_epi32(bx, ax), dy = _mm512_sub_epi32(by, ay);
    const major_steps steps(ax, ay, bx, by, w, h);
    const __mmask16 xm = steps.x_major, rising = steps.rising;
    const __m512i major_a = _mm512_mask_blend_epi32(xm, ay, ax), minor_a = _mm512_mask_blend_epi32(xm, ax, ay);
    const __m512i d_major = _mm512_mask_blend_epi32(xm, dy, dx), d_minor = _mm512_mask_blend_epi32(xm, dx, dy);
    const __m512i first = steps.first, last = steps.last, m_begin = steps.m_begin;
    _mm512_store_si512(b.m_begin, m_begin);
    _mm512_store_si512(b.count, steps.count);
    _mm512_store_si512(b.minor_extent, _mm512_mask_blend_epi32(xm, _mm512_set1_epi32(w), _mm512_set1_epi32(h)));
    // The minor coordinate at m_begin, num0 / denom, and its step per texel: exact integers in doubles.
    const __m512i denom = _mm512_slli_epi32(_mm512_abs_epi32(d_major), bits);
    const __m512i d_minor_signed = _mm512_mask_sub_epi32(d_minor, __mmask16(~rising), zero, d_minor); // sign(d_major) d_minor
    const __m512i offset = _mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(m_begin, bits), half), major_a);
    const __m512i d_major_abs = _mm512_abs_epi32(d_major);
    // sign (minor_a d_major + offset d_minor) = minor_a |d_major| + offset sign d_minor
    const __m512d num_low = _mm512_add_pd(_mm512_mul_pd(low_pd(minor_a), low_pd(d_major_abs)), _mm512_mul_pd(low_pd(offset), low_pd(d_minor_signed)));
    const __m512d num_high = _mm512_add_pd(_mm512_mul_pd(high_pd(minor_a), high_pd(d_major_abs)), _mm512_mul_pd(high_pd(offset), high_pd(d_minor_signed)));
    _mm512_store_pd(b.num0, num_low);
    _mm512_store_pd(b.num0 + 8, num_high);
    const __m512i step = _mm512_slli_epi32(d_minor_signed, bits);
    _mm512_store_pd(b.step, low_pd(step));
    _mm512_store_pd(b.step + 8, high_pd(step));
    const __m512d ones = _mm512_set1_pd(1.0);
    _mm512_store_pd(b.denom, low_pd(denom));
    _mm512_store_pd(b.denom + 8, high_pd(denom));
    _mm512_store_pd(b.inv_denom, _mm512_div_pd(ones, low_pd(denom)));
    _mm512_store_pd(b.inv_denom + 8, _mm512_div_pd(ones, high_pd(denom)));
    // 1 / |d|^2 in float, as segment_shader takes it: products rounded on their own, then an IEEE division.
    const __m512 dx_f = _mm512_cvtepi32_ps(dx), dy_f = _mm512_cvtepi32_ps(dy);
    _mm512_store_ps(b.inv_length2, _mm512_div_ps(_mm512_set1_ps(1.0f), rounded(_mm512_add_ps(rounded(_mm512_mul_ps(dx_f, dx_f)), rounded(_mm512_mul_ps(dy_f, dy_f))))));
    // Ties on the minor axis go to the lower row or left column unless the line is x-major and rising.
    const __mmask16 opposite = __mmask16(_mm512_cmpgt_epi32_mask(dx, zero) ^ _mm512_cmpgt_epi32_mask(dy, zero));
    b.tie = std::uint16_t(__mmask16(~xm) | _mm512_cmpeq_epi32_mask(dy, zero) | opposite);
    b.x_major = xm;
    // The texel whose diamond holds the end makes no fragment.
    const __m512i cx[2] = {texel_of(_mm512_sub_epi32(bx, one)), texel_of(bx)}, cy[2] = {texel_of(_mm512_sub_epi32(by, one)), texel_of(by)};
    __m512i end_x = _mm512_set1_epi32(-(1 << 30)), end_y = end_x; // no texel of the tile
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            const __mmask16 in = inside_diamond(bx, by, cx[i], cy[j]);
            end_x = _mm512_mask_mov_epi32(end_x, in, cx[i]);
            end_y = _mm512_mask_mov_epi32(end_y, in, cy[j]);
        }
    _mm512_store_si512(b.end_major, _mm512_mask_blend_epi32(xm, end_y, end_x));
    _mm512_store_si512(b.end_minor, _mm512_mask_blend_epi32(xm, end_x, end_y));
    // A start inside a diamond whose centre line the segment does not cross still exits it.
    const __m512i sx = texel_of(_mm512_sub_epi32(ax, one)), sy = texel_of(_mm512_sub_epi32(ay, one));
    const __m512i s_major = _mm512_mask_blend_epi32(xm, sy, sx);
    const __mmask16 outside_walk = _mm512_cmplt_epi32_mask(s_major, first) | _mm512_cmpgt_epi32_mask(s_major, last);
    const __mmask16 in_tile = _mm512_cmplt_epu32_mask(sx, _mm512_set1_epi32(w)) & _mm512_cmplt_epu32_mask(sy, _mm512_set1_epi32(h));
    b.start = std::uint16_t(inside_diamond(ax, ay, sx, sy) & outside_walk & __mmask16(~inside_diamond(bx, by, sx, sy)) & in_tile);
    _mm512_store_si512(b.start_x, sx);
    _mm512_store_si512(b.start_y, sy);
    // Its depth, as the walk computes a fragment's.
    _mm512_store_ps(b.start_depth, b.depths().at(sx, sy));
}

/// Rows become columns: r[i][c] moves to r[c][i], for sixteen rows of sixteen 32-bit lanes, in 64
/// shuffles (pairs of lanes, then pairs of pairs, then 128-bit quarters twice).
HAIRSHADOW_AVX512_TARGET inline void transpose(__m512i r[16]) noexcept {
    __m512i t[16], u[16];
    for (int i = 0; i < 16; i += 2) t[i] = _mm512_unpacklo_epi32(r[i], r[i + 1]), t[i + 1] = _mm512_unpackhi_epi32(r[i], r[i + 1]);
    // u[4g + j]: in 128-bit quarter k, column 4k + j of rows 4g .. 4g + 3.
    for (int g = 0; g < 16; g += 4) {
        u[g] = _mm512_unpacklo_epi64(t[g], t[g + 2]), u[g + 1] = _mm512_unpackhi_epi64(t[g], t[g + 2]);
        u[g + 2] = _mm512_unpacklo_epi64(t[g + 1], t[g + 3]), u[g + 3] = _mm512_unpackhi_epi64(t[g + 1], t[g + 3]);
    }
    for (int j = 0; j < 4; ++j) {
        const __m512i low01 = _mm512_shuffle_i32x4(u[j], u[4 + j], 0x44), high01 = _mm512_shuffle_i32x4(u[j], u[4 + j], 0xEE);
        const __m512i low23 = _mm512_shuffle_i32x4(u[8 + j], u[12 + j], 0x44), high23 = _mm512_shuffle_i32x4(u[8 + j], u[12 + j], 0xEE);
        r[j] = _mm512_shuffle_i32x4(low01, low23, 0x88), r[4 + j] = _mm512_shuffle_i32x4(low01, low23, 0xDD);
        r[8 + j] = _mm512_shuffle_i32x4(high01, high23, 0x88), r[12 + j] = _mm512_shuffle_i32x4(high01, high23, 0xDD);
    }
}

/// A step that makes no fragment, in a lockstep block.
inline constexpr std::uint32_t no_texel = 0xFFFFFFFFu;

/// Sixteen segments of a batch walked side by side, one step of each at a time, from the first: the
/// arithmetic of the per-segment walk, lane for lane, so that the fragments are the same bits.
struct lockstep {
    __m512i m_begin, counts, end_major, end_minor, minor_extent, width;
    __mmask16 along_x, tie;
    depth_along along;
    carried_quotient minor_at; ///< the minor coordinate at the next step, floor((num0 + j step) / denom)

    HAIRSHADOW_AVX512_TARGET lockstep(const batch& b, int w) noexcept
        : m_begin(_mm512_load_si512(b.m_begin)), counts(_mm512_load_si512(b.count)), end_major(_mm512_load_si512(b.end_major)),
          end_minor(_mm512_load_si512(b.end_minor)), minor_extent(_mm512_load_si512(b.minor_extent)), width(_mm512_set1_epi32(w)),
          along_x(b.x_major), tie(b.tie), along(b.depths()) {
        __m512d part[8];
        const __m512d denom_low = _mm512_load_pd(b.denom), denom_high = _mm512_load_pd(b.denom + 8);
        const __m512d inv_denom_low = _mm512_load_pd(b.inv_denom), inv_denom_high = _mm512_load_pd(b.inv_denom + 8);
        exact_quotient(_mm512_load_pd(b.num0), denom_low, inv_denom_low, part[0], part[1]);
        exact_quotient(_mm512_load_pd(b.num0 + 8), denom_high, inv_denom_high, part[2], part[3]);
        exact_quotient(_mm512_load_pd(b.step), denom_low, inv_denom_low, part[4], part[5]);
        exact_quotient(_mm512_load_pd(b.step + 8), denom_high, inv_denom_high, part[6], part[7]);
        minor_at = {integers_of(part[0], part[2]), integers_of(part[1], part[3]), integers_of(part[4], part[6]), integers_of(part[5], part[7]),
                    integers_of(denom_low, denom_high)};
    }
    /// Step j, the one after the last taken: each lane's texel index (no_texel where it makes no
    /// fragment) and its depth.
    HAIRSHADOW_AVX512_TARGET __m512i step(int j, __m512& depth) noexcept {
        const __m512i i = _mm512_set1_epi32(j);
        const __m512i minor = minor_at.minor(tie);
        minor_at.advance();
        __m512i x, y;
        const __m512i where = step_texels(_mm512_add_epi32(m_begin, i), minor, _mm512_cmpgt_epi32_mask(counts, i), along_x, end_major, end_minor,
                                          minor_extent, width, _mm512_set1_epi32(std::int32_t(no_texel)), x, y);
        depth = along.at(x, y);
        return where;
    }
};

/// The first `steps` (at most 16) texels of the sixteen segments of b at once, one segment per lane:
/// step j's texel indices (no_texel where it makes no fragment) in where[j], its depths in depth[j];
/// rows past `steps` make no fragment.
HAIRSHADOW_AVX512_TARGET inline void walk_lockstep(const batch& b, int steps, int w, __m512i where[16], __m512i depth[16]) noexcept {
    lockstep walk(b, w);
    for (int j = 0; j < steps; ++j) {
        __m512 d;
        where[j] = walk.step(j, d);
        depth[j] = _mm512_castps_si512(d);
    }
    for (int j = steps; j < 16; ++j) where[j] = _mm512_set1_epi32(std::int32_t(no_texel)), depth[j] = _mm512_setzero_si512();
}

/// Bounds that keep every product of the walk exact in a double and every coordinate in 32 bits: a
/// segment longer, or further from its tile, is walked by the scalar code.
inline constexpr std::int64_t most_length = std::int64_t(1) << 22, most_coordinate = std::int64_t(1) << 24;

/// The batch's ends and depths for the first `lanes` segments of `list`, in coordinates relative to
/// the tile's corner (ox, oy), one lane at a time. Lanes that do not fit the walk's bounds, or whose
/// 1/w differ (perspective interpolation), are left to the scalar walk (not in b.simd) with a
/// harmless stand-in.
inline void fill_batch(batch& b, const segment_bins& bins, const std::uint32_t* list, int lanes, std::int64_t ox, std::int64_t oy) noexcept {
    b.simd = 0;
    for (int l = 0; l < 16; ++l) {
        if (l < lanes) {
            const prepared_segment s = bins.segment(list[l]);
            const std::int64_t ax = s.ax - ox, ay = s.ay - oy, bx = s.bx - ox, by = s.by - oy;
            const bool fits = s.inv_w_a == s.inv_w_b && std::abs(bx - ax) < most_length && std::abs(by - ay) < most_length &&
                              std::max({std::abs(ax), std::abs(ay), std::abs(bx), std::abs(by)}) < most_coordinate;
            if (fits) {
                b.ax[l] = std::int32_t(ax), b.ay[l] = std::int32_t(ay), b.bx[l] = std::int32_t(bx), b.by[l] = std::int32_t(by);
                b.depth_a[l] = s.depth_a;
                b.depth_delta[l] = s.depth_b - s.depth_a;
                b.simd = std::uint16_t(b.simd | (1u << l));
                continue;
            }
        }
        b.ax[l] = 0, b.ay[l] = 0, b.bx[l] = std::int32_t(subpixel_scale), b.by[l] = 0; // a harmless stand-in
        b.depth_a[l] = 0.0f, b.depth_delta[l] = 0.0f;
    }
}

/// The ends of the first `lanes` segments of `list` (zero in the other lanes), gathered from the
/// records by 32-bit word offsets (segment_count() below 2^28) and made relative to the tile's corner
/// (ox, oy) in sub-pixels; `words` are the records' first words.
struct gathered_ends {
    __m512i words, ax, ay, bx, by;

    HAIRSHADOW_AVX512_TARGET gathered_ends(const segment_bins& bins, const std::uint32_t* list, int lanes, std::int32_t ox, std::int32_t oy) noexcept {
        static_assert(sizeof(segment_geometry) == 6 * sizeof(std::int32_t));
        const auto valid = __mmask16((1u << lanes) - 1u);
        const __m512i zero = _mm512_setzero_si512();
        const void* records = bins.segment_data();
        words = _mm512_mullo_epi32(_mm512_maskz_loadu_epi32(valid, list), _mm512_set1_epi32(6));
        __m512i field[4];
        for (int k = 0; k < 4; ++k)
            field[k] = _mm512_sub_epi32(_mm512_mask_i32gather_epi32(zero, valid, _mm512_add_epi32(words, _mm512_set1_epi32(k)), records, 4),
                                        _mm512_set1_epi32(k % 2 == 0 ? ox : oy));
        ax = field[0], ay = field[1], bx = field[2], by = field[3];
    }
};

/// Fetches into the cache the records of the sixteen segments `ahead` on from `base` in `list` (by
/// default the next batch's). Always inlined: GCC finds a function that only prefetches free of side
/// effects, and deletes its calls.
HAIRSHADOW_ALWAYS_INLINE inline void prefetch_next_batch(const segment_bins& bins, std::span<const std::uint32_t> list, std::size_t base,
                                                          std::size_t ahead = 16) noexcept {
    for (std::size_t i = base + ahead; i < std::min(base + ahead + 16, list.size()); ++i) bins.prefetch_segment(list[i]);
}

/// fill_batch, sixteen lanes at once: the records gathered by word offsets (segment_count() below
/// 2^28), the same values and the same b.simd. Coordinates inside the guard band (2^28 sub-pixels)
/// less a tile corner below 2^24 fit in 32 bits, and so do their differences.
HAIRSHADOW_AVX512_TARGET inline void gather_batch(batch& b, const segment_bins& bins, const std::uint32_t* list, int lanes, std::int32_t ox,
                                                 std::int32_t oy) noexcept {
    const auto valid = __mmask16((1u << lanes) - 1u);
    const gathered_ends ends(bins, list, lanes, ox, oy);
    const __m512i ax = ends.ax, ay = ends.ay, bx = ends.bx, by = ends.by;
    const void* records = bins.segment_data();
    const __m512 depth_a = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), valid, _mm512_add_epi32(ends.words, _mm512_set1_epi32(4)), records, 4);
    const __m512 depth_b = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), valid, _mm512_add_epi32(ends.words, _mm512_set1_epi32(5)), records, 4);
    __mmask16 fits = valid;
    if (const auto* inv_w = bins.inv_w_data()) {
        const __m512i pairs = _mm512_slli_epi32(_mm512_maskz_loadu_epi32(valid, list), 1);
        const __m512 inv_w_a = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), valid, pairs, inv_w, 4);
        const __m512 inv_w_b = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), valid, _mm512_add_epi32(pairs, _mm512_set1_epi32(1)), inv_w, 4);
        fits &= _mm512_cmp_ps_mask(inv_w_a, inv_w_b, _CMP_EQ_OQ);
    }
    const __m512i length = _mm512_set1_epi32(std::int32_t(most_length)), coordinate = _mm512_set1_epi32(std::int32_t(most_coordinate));
    fits &= __mmask16(_mm512_cmplt_epi32_mask(_mm512_abs_epi32(_mm512_sub_epi32(bx, ax)), length) &
                      _mm512_cmplt_epi32_mask(_mm512_abs_epi32(_mm512_sub_epi32(by, ay)), length));
    const __m512i farthest = _mm512_max_epi32(_mm512_max_epi32(_mm512_abs_epi32(ax), _mm512_abs_epi32(ay)), _mm512_max_epi32(_mm512_abs_epi32(bx), _mm512_abs_epi32(by)));
    fits &= _mm512_cmplt_epi32_mask(farthest, coordinate);
    _mm512_store_si512(b.ax, _mm512_maskz_mov_epi32(fits, ax));
    _mm512_store_si512(b.ay, _mm512_maskz_mov_epi32(fits, ay));
    _mm512_store_si512(b.bx, _mm512_mask_mov_epi32(_mm512_set1_epi32(std::int32_t(subpixel_scale)), fits, bx));
    _mm512_store_si512(b.by, _mm512_maskz_mov_epi32(fits, by));
    _mm512_store_ps(b.depth_a, _mm512_maskz_mov_ps(fits, depth_a));
    _mm512_store_ps(b.depth_delta, _mm512_maskz_mov_ps(fits, _mm512_sub_ps(depth_b, depth_a)));
    b.simd = fits;
}

/// Puts the start fragment of each of `lanes` (a lockstep block's, before its transpose) in the row
/// after the lane's last step, where its walk leaves no fragment, so that it is stored with them, after
/// them, as the scalar walk stores it. Returns the lanes so placed: those with a start fragment and
/// fewer than sixteen steps; the others' start is stored apart.
HAIRSHADOW_AVX512_TARGET inline __mmask16 place_starts(const batch& b, __mmask16 lanes, int w, __m512i where[16], __m512i depth[16]) noexcept {
    const __m512i counts = _mm512_load_si512(b.count);
    const __mmask16 in_row = lanes & b.start & _mm512_cmplt_epi32_mask(counts, _mm512_set1_epi32(16));
    if (in_row == 0) return 0;
    const __m512i texel = _mm512_add_epi32(_mm512_mullo_epi32(_mm512_load_si512(b.start_y), _mm512_set1_epi32(w)), _mm512_load_si512(b.start_x));
    const __m512i start_depth = _mm512_castps_si512(_mm512_load_ps(b.start_depth));
    for (int j = 0; j < 16; ++j) {
        const __mmask16 here = in_row & _mm512_cmpeq_epi32_mask(counts, _mm512_set1_epi32(j));
        where[j] = _mm512_mask_mov_epi32(where[j], here, texel);
        depth[j] = _mm512_mask_mov_epi32(depth[j], here, start_depth);
    }
    return in_row;
}

} // namespace hairshadow::detail::avx512
