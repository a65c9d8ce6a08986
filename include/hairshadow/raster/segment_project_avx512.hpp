#pragma once
/// @file
/// The projection and binning of segment_bins in AVX-512F, sixteen segments of a strand at a time:
/// both ends projected (light_space::project, product by product as it rounds them), the near and
/// far planes and the guard band checked, the ends snapped, and the segment counted in its tile when
/// it lies in one tile. Segments that need clipping, or that reach several tiles, go through the
/// scalar code, lane by lane, in order; so every segment, count and first tile is the scalar one.

#include <hairshadow/raster/segment_bins.hpp>

#include <hairshadow/raster/instruction_set.hpp>

#include <bit>
#include <cstdint>

namespace hairshadow::detail {

namespace avx512 {

/// c v, rounded (no fused multiply-add: see detail::rounded).
HAIRSHADOW_AVX512_TARGET inline __m512 product(float c, __m512 v) noexcept { return rounded(_mm512_mul_ps(_mm512_set1_ps(c), v)); }

/// Row i of m (p, 1) for sixteen points, as light_space::row rounds it.
HAIRSHADOW_AVX512_TARGET inline __m512 project_row(const std::array<float, 4>& m, __m512 x, __m512 y, __m512 z) noexcept {
    return _mm512_add_ps(_mm512_add_ps(product(m[0], x), product(m[1], y)), _mm512_add_ps(product(m[2], z), _mm512_set1_ps(m[3])));
}

/// -v, exactly as the scalar negation (the sign bit flipped; 0 - v would give +0 for +0).
HAIRSHADOW_AVX512_TARGET inline __m512 negate(__m512 v) noexcept {
    return _mm512_castsi512_ps(_mm512_xor_epi32(_mm512_castps_si512(v), _mm512_set1_epi32(std::int32_t(0x80000000u))));
}

/// snap() for eight window coordinates: x S + copysign(1/2, x), truncated, in doubles.
HAIRSHADOW_AVX512_TARGET inline __m256i snap8(__m256 window) noexcept {
    const __m512d x = _mm512_mul_pd(_mm512_cvtps_pd(window), _mm512_set1_pd(double(subpixel_scale)));
    const __m512i sign = _mm512_set1_epi64(std::int64_t(0x8000000000000000ull)), half = _mm512_castpd_si512(_mm512_set1_pd(0.5));
    const __m512d h = _mm512_castsi512_pd(_mm512_or_si512(_mm512_and_si512(_mm512_castpd_si512(x), sign), half));
    return _mm512_cvttpd_epi32(_mm512_add_pd(x, h));
}

/// snap() for sixteen window coordinates.
HAIRSHADOW_AVX512_TARGET inline __m512i snap16(__m512 window) noexcept {
    const __m256 low = _mm512_castps512_ps256(window);
    const __m256 high = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(window), 1));
    return _mm512_inserti64x4(_mm512_castsi256_si512(snap8(low)), snap8(high), 1);
}

/// |v| <= limit, lane by lane (false for NaN).
HAIRSHADOW_AVX512_TARGET inline __mmask16 within(__m512 v, __m512 limit) noexcept { return _mm512_cmp_ps_mask(_mm512_abs_ps(v), limit, _CMP_LE_OQ); }

/// Floats at byte offsets 4 (at + offset) from `from`, in the `valid` lanes (0 elsewhere).
HAIRSHADOW_AVX512_TARGET inline __m512 gather_floats(const float* from, __m512i at, int offset, __mmask16 valid) noexcept {
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), valid, _mm512_add_epi32(at, _mm512_set1_epi32(offset)), from, 4);
}

} // namespace avx512

HAIRSHADOW_AVX512_TARGET inline void segment_bins::project_strand_avx512(const glm::vec3* points, std::size_t n, std::size_t first_seg,
                                                                         std::uint64_t* counts, std::uint64_t* bounds, depth_extent& e,
                                                                         std::int64_t reach) {
    using namespace avx512;
    const light_space& ls = light_;
    const auto vp_x = ls.row_coefficients(ls.view_projection(), 0), vp_y = ls.row_coefficients(ls.view_projection(), 1);
    const auto vp_w = ls.row_coefficients(ls.view_projection(), 3), view_z = ls.row_coefficients(ls.view(), 2);
    const __m512 half_res = _mm512_set1_ps(0.5f * float(res_)), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
    const __m512 near_plane = _mm512_set1_ps(ls.near_plane()), far_plane = _mm512_set1_ps(ls.far_plane());
    const __m512 depth_span = _mm512_set1_ps(ls.far_plane() - ls.near_plane());
    const __m512 guard = _mm512_set1_ps(guard_band), two = _mm512_set1_ps(2.0f);
    const __m512i lane3 = _mm512_mullo_epi32(_mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0), _mm512_set1_epi32(3));
    const __m512i reach_v = _mm512_set1_epi32(std::int32_t(reach)), res_v = _mm512_set1_epi32(res_), last_v = _mm512_set1_epi32(res_ - 1);
    const int tile_shift = std::countr_zero(unsigned(opt_.tile_size));
    const __m512i tiles_x = _mm512_set1_epi32(tiles_x_), zero_i = _mm512_setzero_si512();
    __m512 nearest = _mm512_set1_ps(e.nearest), furthest = _mm512_set1_ps(e.furthest);
    alignas(64) std::int32_t ax[16], ay[16], bx[16], by[16], tile[16], bound[16];
    const __m512i most_bound = _mm512_set1_epi32(opt_.tile_size + 1), two_i = _mm512_set1_epi32(2);
    alignas(64) float depth_a[16], depth_b[16], inv_w_a[16], inv_w_b[16];
    const std::size_t segments = n - 1;
    for (std::size_t base = 0; base < segments; base += 16) {
        const auto lanes = int(std::min<std::size_t>(16, segments - base));
        const auto valid = __mmask16((1u << lanes) - 1u);
        // Both ends of each segment: points base + l and base + l + 1.
        const float* from = &points[base].x;
        const __m512 x0 = gather_floats(from, lane3, 0, valid), y0 = gather_floats(from, lane3, 1, valid), z0 = gather_floats(from, lane3, 2, valid);
        const __m512 x1 = gather_floats(from, lane3, 3, valid), y1 = gather_floats(from, lane3, 4, valid), z1 = gather_floats(from, lane3, 5, valid);
        const __m512 d0 = negate(project_row(view_z, x0, y0, z0)), d1 = negate(project_row(view_z, x1, y1, z1));
        // No clipping at the near and far planes (prepare_segment's tests, in its own arithmetic).
        auto simple = __mmask16(valid & _mm512_cmp_ps_mask(_mm512_sub_ps(d0, near_plane), zero, _CMP_GE_OQ) &
                           _mm512_cmp_ps_mask(_mm512_sub_ps(d1, near_plane), zero, _CMP_GE_OQ) &
                           _mm512_cmp_ps_mask(_mm512_sub_ps(far_plane, d0), zero, _CMP_GE_OQ) &
                           _mm512_cmp_ps_mask(_mm512_sub_ps(far_plane, d1), zero, _CMP_GE_OQ));
        const __m512 w0 = project_row(vp_w, x0, y0, z0), w1 = project_row(vp_w, x1, y1, z1);
        const __m512 wx0 = _mm512_mul_ps(_mm512_add_ps(_mm512_div_ps(project_row(vp_x, x0, y0, z0), w0), one), half_res);
        const __m512 wy0 = _mm512_mul_ps(_mm512_add_ps(_mm512_div_ps(project_row(vp_y, x0, y0, z0), w0), one), half_res);
        const __m512 wx1 = _mm512_mul_ps(_mm512_add_ps(_mm512_div_ps(project_row(vp_x, x1, y1, z1), w1), one), half_res);
        const __m512 wy1 = _mm512_mul_ps(_mm512_add_ps(_mm512_div_ps(project_row(vp_y, x1, y1, z1), w1), one), half_res);
        const __m512 dep0 = _mm512_div_ps(_mm512_sub_ps(d0, near_plane), depth_span), dep1 = _mm512_div_ps(_mm512_sub_ps(d1, near_plane), depth_span);
        // Inside the guard band, finite, in front of the light: prepare_segment's last test.
        simple = __mmask16(simple & within(wx0, guard) & within(wy0, guard) & within(wx1, guard) & within(wy1, guard) & within(dep0, two) &
                           within(dep1, two) & _mm512_cmp_ps_mask(w0, zero, _CMP_GT_OQ) & _mm512_cmp_ps_mask(w1, zero, _CMP_GT_OQ));
        const __m512i sax = snap16(wx0), say = snap16(wy0), sbx = snap16(wx1), sby = snap16(wy1);
        _mm512_store_si512(ax, sax);
        _mm512_store_si512(ay, say);
        _mm512_store_si512(bx, sbx);
        _mm512_store_si512(by, sby);
        _mm512_store_ps(depth_a, dep0);
        _mm512_store_ps(depth_b, dep1);
        _mm512_store_ps(inv_w_a, _mm512_div_ps(one, w0));
        _mm512_store_ps(inv_w_b, _mm512_div_ps(one, w1));
        // One tile, inside the map: counted here; anything else goes through the scalar code.
        const __mmask16 empty = _mm512_cmpeq_epi32_mask(sax, sbx) & _mm512_cmpeq_epi32_mask(say, sby);
        const __m512i lo_x = _mm512_srai_epi32(_mm512_sub_epi32(_mm512_min_epi32(sax, sbx), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
        const __m512i hi_x = _mm512_srai_epi32(_mm512_add_epi32(_mm512_max_epi32(sax, sbx), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
        const __m512i lo_y = _mm512_srai_epi32(_mm512_sub_epi32(_mm512_min_epi32(say, sby), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
        const __m512i hi_y = _mm512_srai_epi32(_mm512_add_epi32(_mm512_max_epi32(say, sby), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
        const __mmask16 in_map = _mm512_cmpge_epi32_mask(hi_x, zero_i) & _mm512_cmpge_epi32_mask(hi_y, zero_i) &
                                 _mm512_cmplt_epi32_mask(lo_x, res_v) & _mm512_cmplt_epi32_mask(lo_y, res_v);
        const __m512i tx0 = _mm512_srai_epi32(_mm512_max_epi32(lo_x, zero_i), tile_shift), tx1 = _mm512_srai_epi32(_mm512_min_epi32(hi_x, last_v), tile_shift);
        const __m512i ty0 = _mm512_srai_epi32(_mm512_max_epi32(lo_y, zero_i), tile_shift), ty1 = _mm512_srai_epi32(_mm512_min_epi32(hi_y, last_v), tile_shift);
        const __mmask16 one_tile = simple & __mmask16(~empty) & in_map & _mm512_cmpeq_epi32_mask(tx0, tx1) & _mm512_cmpeq_epi32_mask(ty0, ty1);
        const __mmask16 off_map = simple & __mmask16(~empty) & __mmask16(~in_map);
        _mm512_store_si512(tile, _mm512_add_epi32(_mm512_mullo_epi32(ty0, tiles_x), tx0));
        // segment_fragment_bound; within the guard band the differences fit in 32 bits.
        const __m512i major = _mm512_max_epi32(_mm512_abs_epi32(_mm512_sub_epi32(sbx, sax)), _mm512_abs_epi32(_mm512_sub_epi32(sby, say)));
        _mm512_store_si512(bound, _mm512_min_epi32(_mm512_add_epi32(_mm512_srai_epi32(major, HAIRSHADOW_SUBPIXEL_BITS), two_i), most_bound));
        const __mmask16 meets_map = simple & __mmask16(~empty) & in_map; // the extent counts these (segment_bins::meets_map)
        nearest = _mm512_mask_min_ps(nearest, meets_map, nearest, _mm512_min_ps(dep0, dep1));
        furthest = _mm512_mask_max_ps(furthest, meets_map, furthest, _mm512_max_ps(dep0, dep1));
        for (int l = 0; l < lanes; ++l) {
            const std::size_t i = base + std::size_t(l), seg = first_seg + i;
            const std::uint32_t bit = 1u << l;
            if (simple & bit) {
                store(seg, {{ax[l], ay[l], bx[l], by[l], depth_a[l], depth_b[l]}, inv_w_a[l], inv_w_b[l]});
                if (one_tile & bit) {
                    ++counts[tile[l]];
                    if (bounds) bounds[tile[l]] += std::uint64_t(bound[l]);
                    first_tile_[seg] = std::uint32_t(tile[l]);
                    continue;
                }
                if ((empty | off_map) & bit) {
                    first_tile_[seg] = no_tile;
                    continue;
                }
            }
            first_tile_[seg] = prepare_and_count(points[i], points[i + 1], (simple & bit) != 0, seg, reach, counts, bounds, e);
        }
    }
    e.nearest = std::min(e.nearest, _mm512_reduce_min_ps(nearest));
    e.furthest = std::max(e.furthest, _mm512_reduce_max_ps(furthest));
}

} // namespace hairshadow::detail
