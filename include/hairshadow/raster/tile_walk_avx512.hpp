#pragma once
/// @file
/// The tiled build's line walk in AVX-512F, chosen at run time (raster_options::instructions). Sixteen
/// segments of a tile are set up at once, one per lane: major axis, the texel centres they cross in
/// the tile, the exact quotient and remainder of the minor coordinate, the end's diamond and the start
/// fragment (the diamond-exit rule of line_rule.hpp, without a branch). Then each segment is walked
/// sixteen texels at a time, one per lane, and its fragments are compressed into the tile's store in
/// order, so that segment order, and every sum, is the scalar walk's. Every quantity is an integer,
/// or an integer held exactly in a double, until the depth: that is a + (b - a) t, rounded as the
/// scalar walk rounds it.

#include <hairshadow/raster/tile_fragments.hpp>

#include <cstdint>

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

/// q = floor(num / denom) for integers num and denom > 0 held exactly in doubles (|num| < 2^52), and
/// whether denom divides num. The product with 1 / denom misses the quotient by far less than one, so
/// one correction each way makes it exact, with no division on the walk's path.
HAIRSHADOW_AVX512_TARGET inline __mmask8 exact_quotient(__m512d num, __m512d denom, __m512d inv_denom, __m512d& q) noexcept {
    q = _mm512_roundscale_pd(_mm512_mul_pd(num, inv_denom), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    __m512d rem = _mm512_sub_pd(num, _mm512_mul_pd(q, denom)); // exact: integers below 2^53
    const __mmask8 below = _mm512_cmp_pd_mask(rem, _mm512_setzero_pd(), _CMP_LT_OQ);
    q = _mm512_mask_sub_pd(q, below, q, _mm512_set1_pd(1.0));
    rem = _mm512_mask_add_pd(rem, below, rem, denom);
    const __mmask8 above = _mm512_cmp_pd_mask(rem, denom, _CMP_GE_OQ);
    q = _mm512_mask_add_pd(q, above, q, _mm512_set1_pd(1.0));
    rem = _mm512_mask_sub_pd(rem, above, rem, denom);
    return _mm512_cmp_pd_mask(rem, _mm512_setzero_pd(), _CMP_EQ_OQ);
}

/// Lane halves as doubles.
HAIRSHADOW_AVX512_TARGET inline __m512d low_pd(__m512i x) noexcept { return _mm512_cvtepi32_pd(_mm512_castsi512_si256(x)); }
HAIRSHADOW_AVX512_TARGET inline __m512d high_pd(__m512i x) noexcept { return _mm512_cvtepi32_pd(_mm512_extracti64x4_epi64(x, 1)); }
HAIRSHADOW_AVX512_TARGET inline __m512i join_epi32(__m256i low, __m256i high) noexcept {
    return _mm512_inserti64x4(_mm512_castsi256_si512(low), high, 1);
}
HAIRSHADOW_AVX512_TARGET inline __m512 join_ps(__m256 low, __m256 high) noexcept {
    return _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castps_pd(_mm512_castps256_ps512(low)), _mm256_castps_pd(high), 1));
}

/// Sixteen segments set up for the walk, in tile-relative coordinates (sub-pixels for ends, texels
/// for the rest). Lanes not `simd` are walked in scalar.
struct alignas(64) batch {
    std::int32_t ax[16], ay[16], bx[16], by[16];
    std::int32_t m_begin[16], count[16], end_major[16], end_minor[16], minor_extent[16], start_x[16], start_y[16];
    double num0[16], step[16], denom[16], inv_denom[16], inv_length2[16];
    float start_depth[16];
    float depth_a[16], depth_delta[16];
    std::uint16_t x_major, tie, start, simd;
};

/// Vector set-up of the sixteen segments in b.ax..b.by for a tile of w x h texels: walk_line's
/// quantities, lane by lane.
HAIRSHADOW_AVX512_TARGET inline void set_up(batch& b, int w, int h) noexcept {
    constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
    const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi32(1);
    const __m512i half = _mm512_set1_epi32(std::int32_t(subpixel_scale / 2));
    const __m512i ax = _mm512_load_si512(b.ax), ay = _mm512_load_si512(b.ay), bx = _mm512_load_si512(b.bx), by = _mm512_load_si512(b.by);
    const __m512i dx = _mm512_sub_epi32(bx, ax), dy = _mm512_sub_epi32(by, ay);
    const __mmask16 xm = _mm512_cmpge_epi32_mask(_mm512_abs_epi32(dx), _mm512_abs_epi32(dy));
    const __m512i major_a = _mm512_mask_blend_epi32(xm, ay, ax), major_b = _mm512_mask_blend_epi32(xm, by, bx);
    const __m512i minor_a = _mm512_mask_blend_epi32(xm, ax, ay);
    const __m512i d_major = _mm512_mask_blend_epi32(xm, dy, dx), d_minor = _mm512_mask_blend_epi32(xm, dx, dy);
    const __mmask16 rising = _mm512_cmpgt_epi32_mask(d_major, zero);
    const __m512i lo_end = _mm512_mask_blend_epi32(rising, major_b, major_a), hi_end = _mm512_mask_blend_epi32(rising, major_a, major_b);
    // Centres c S + H crossed: first = ceil((lo - H) / S), last = ceil((hi - H) / S) - 1.
    const __m512i round_up = _mm512_set1_epi32(std::int32_t(subpixel_scale - 1 - subpixel_scale / 2));
    const __m512i first = texel_of(_mm512_add_epi32(lo_end, round_up));
    const __m512i last = _mm512_sub_epi32(texel_of(_mm512_add_epi32(hi_end, round_up)), one);
    const __m512i extent = _mm512_mask_blend_epi32(xm, _mm512_set1_epi32(h), _mm512_set1_epi32(w));
    const __m512i m_begin = _mm512_max_epi32(first, zero), m_end = _mm512_min_epi32(last, _mm512_sub_epi32(extent, one));
    _mm512_store_si512(b.m_begin, m_begin);
    _mm512_store_si512(b.count, _mm512_max_epi32(_mm512_add_epi32(_mm512_sub_epi32(m_end, m_begin), one), zero));
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
    _mm512_store_pd(b.inv_length2, _mm512_div_pd(ones, _mm512_add_pd(_mm512_mul_pd(low_pd(dx), low_pd(dx)), _mm512_mul_pd(low_pd(dy), low_pd(dy)))));
    _mm512_store_pd(b.inv_length2 + 8,
                    _mm512_div_pd(ones, _mm512_add_pd(_mm512_mul_pd(high_pd(dx), high_pd(dx)), _mm512_mul_pd(high_pd(dy), high_pd(dy)))));
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
    // Its depth, as the walk computes a fragment's (segment_shader::parameter, lerp_exact).
    const __m512i px = _mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(sx, bits), half), ax);
    const __m512i py = _mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(sy, bits), half), ay);
    const __m512d zero_pd = _mm512_setzero_pd();
    const __m512d t_low = _mm512_max_pd(_mm512_min_pd(_mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(low_pd(px), low_pd(dx)), _mm512_mul_pd(low_pd(py), low_pd(dy))),
                                                                    _mm512_load_pd(b.inv_length2)), ones), zero_pd);
    const __m512d t_high = _mm512_max_pd(_mm512_min_pd(_mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(high_pd(px), high_pd(dx)), _mm512_mul_pd(high_pd(py), high_pd(dy))),
                                                                     _mm512_load_pd(b.inv_length2 + 8)), ones), zero_pd);
    const __m512 param = join_ps(_mm512_cvtpd_ps(t_low), _mm512_cvtpd_ps(t_high));
    _mm512_store_ps(b.start_depth, _mm512_add_ps(_mm512_load_ps(b.depth_a), rounded(_mm512_mul_ps(_mm512_load_ps(b.depth_delta), param))));
}

} // namespace hairshadow::detail::avx512

namespace hairshadow::detail {

/// Walks tile t, whose every fragment has optical depth `optical` (simd_tile()).
HAIRSHADOW_AVX512_TARGET inline void tile_fragments::walk_avx512(const segment_bins& bins, std::size_t t, float optical) {
    using namespace avx512;
    constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
    // Bounds that keep every product exact in a double and every coordinate in 32 bits.
    constexpr std::int64_t most_length = std::int64_t(1) << 22, most_coordinate = std::int64_t(1) << 24;
    const int w = width_, h = rect_.y1 - rect_.y0;
    const std::int64_t ox = std::int64_t(rect_.x0) << bits, oy = std::int64_t(rect_.y0) << bits;
    const auto list = bins.tile_segments(t);
    const __m512i iota = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    const __m512i half = _mm512_set1_epi32(std::int32_t(subpixel_scale / 2)), one = _mm512_set1_epi32(1);
    const __m512d zero_pd = _mm512_setzero_pd(), one_pd = _mm512_set1_pd(1.0);
    batch b;
    for (std::size_t base = 0; base < list.size(); base += 16) {
        const int lanes = int(std::min<std::size_t>(16, list.size() - base));
        b.simd = 0;
        for (int l = 0; l < 16; ++l) {
            if (l < lanes) {
#if defined(__GNUC__)
                if (base + std::size_t(l) + 16 < list.size()) __builtin_prefetch(&bins.segment(list[base + std::size_t(l) + 16]));
#endif
                const prepared_segment& s = bins.segment(list[base + std::size_t(l)]);
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
        set_up(b, w, h);
        for (int l = 0; l < lanes; ++l) {
            if (!((b.simd >> l) & 1u)) {
                walk_segment_apart(bins, list[base + std::size_t(l)]);
                continue;
            }
            const int count = b.count[l];
            make_room(std::size_t(count) + 1);
            // Whole-vector stores need 16 slots past n_; near the store's end, compress to memory
            // instead, so that the store grows exactly as the scalar walk's does.
            const bool whole_vectors = n_ + std::size_t(count) + 16 <= where_.size();
            const __mmask16 along_x = (b.x_major >> l) & 1u ? __mmask16(0xFFFF) : __mmask16(0);
            const __mmask16 tie = (b.tie >> l) & 1u ? __mmask16(0xFFFF) : __mmask16(0);
            const __m512i m_begin = _mm512_set1_epi32(b.m_begin[l]), counts = _mm512_set1_epi32(count);
            const __m512i end_major = _mm512_set1_epi32(b.end_major[l]), end_minor = _mm512_set1_epi32(b.end_minor[l]);
            const __m512i minor_extent = _mm512_set1_epi32(b.minor_extent[l]), width = _mm512_set1_epi32(w);
            const __m512i ax = _mm512_set1_epi32(b.ax[l]), ay = _mm512_set1_epi32(b.ay[l]);
            const __m512d num0 = _mm512_set1_pd(b.num0[l]), step = _mm512_set1_pd(b.step[l]), denom = _mm512_set1_pd(b.denom[l]);
            const __m512d inv_denom = _mm512_set1_pd(b.inv_denom[l]);
            const __m512d dx = _mm512_set1_pd(double(b.bx[l] - b.ax[l])), dy = _mm512_set1_pd(double(b.by[l] - b.ay[l]));
            const __m512d inv_length2 = _mm512_set1_pd(b.inv_length2[l]);
            const __m512 depth_a = _mm512_set1_ps(b.depth_a[l]), depth_delta = _mm512_set1_ps(b.depth_delta[l]);
            const __m512 optical_depth = _mm512_set1_ps(optical);
            for (int c = 0; c < count; c += 16) {
                const __m512i i = _mm512_add_epi32(iota, _mm512_set1_epi32(c));
                const __mmask16 active = _mm512_cmplt_epi32_mask(i, counts);
                const __m512i m = _mm512_add_epi32(i, m_begin);
                // minor = floor(num / denom) and whether it divides exactly: exact_quotient.
                __m512d q_low, q_high;
                const __mmask8 tie_low = exact_quotient(_mm512_add_pd(num0, _mm512_mul_pd(low_pd(i), step)), denom, inv_denom, q_low);
                const __mmask8 tie_high = exact_quotient(_mm512_add_pd(num0, _mm512_mul_pd(high_pd(i), step)), denom, inv_denom, q_high);
                const auto on_tie = __mmask16(tie_low | (tie_high << 8));
                const __m512i q = join_epi32(_mm512_cvttpd_epi32(q_low), _mm512_cvttpd_epi32(q_high));
                const __m512i minor = _mm512_mask_sub_epi32(q, __mmask16(on_tie & tie), q, one);
                const __mmask16 at_end = _mm512_cmpeq_epi32_mask(m, end_major) & _mm512_cmpeq_epi32_mask(minor, end_minor);
                const __mmask16 keep = active & _mm512_cmplt_epu32_mask(minor, minor_extent) & __mmask16(~at_end);
                const __m512i x = _mm512_mask_blend_epi32(along_x, minor, m), y = _mm512_mask_blend_epi32(along_x, m, minor);
                const __m512i local = _mm512_add_epi32(_mm512_mullo_epi32(y, width), x);
                // t = ((x S + H - ax) dx + (y S + H - ay) dy) / |d|^2, clamped: segment_shader::parameter.
                const __m512i px = _mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(x, bits), half), ax);
                const __m512i py = _mm512_sub_epi32(_mm512_add_epi32(_mm512_slli_epi32(y, bits), half), ay);
                const __m512d t_low = _mm512_max_pd(
                    _mm512_min_pd(_mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(low_pd(px), dx), _mm512_mul_pd(low_pd(py), dy)), inv_length2), one_pd), zero_pd);
                const __m512d t_high = _mm512_max_pd(
                    _mm512_min_pd(_mm512_mul_pd(_mm512_add_pd(_mm512_mul_pd(high_pd(px), dx), _mm512_mul_pd(high_pd(py), dy)), inv_length2), one_pd), zero_pd);
                const __m512 param = join_ps(_mm512_cvtpd_ps(t_low), _mm512_cvtpd_ps(t_high));
                const __m512 depth = _mm512_add_ps(depth_a, rounded(_mm512_mul_ps(depth_delta, param))); // lerp_exact
                if (whole_vectors) {
                    // Compressed in registers and stored whole, past n_: a compress straight to
                    // memory measured 1.3x slower on this machine's CPU.
                    _mm512_storeu_si512(where_.data() + n_, _mm512_maskz_compress_epi32(keep, local));
                    _mm512_storeu_ps(depth_.data() + n_, _mm512_maskz_compress_ps(keep, depth));
                    _mm512_storeu_ps(optical_.data() + n_, optical_depth);
                } else {
                    _mm512_mask_compressstoreu_epi32(where_.data() + n_, keep, local);
                    _mm512_mask_compressstoreu_ps(depth_.data() + n_, keep, depth);
                    _mm512_mask_compressstoreu_ps(optical_.data() + n_, keep, optical_depth);
                }
                n_ += std::size_t(__builtin_popcount(keep));
            }
            // The start fragment, as walk_line emits it, after the walk; stored always and kept when
            // there is one, since whether there is one is anybody's guess.
            where_[n_] = std::uint32_t(b.start_y[l] * w + b.start_x[l]);
            depth_[n_] = b.start_depth[l];
            optical_[n_] = optical;
            n_ += (b.start >> l) & 1u;
        }
    }
}

} // namespace hairshadow::detail
