#pragma once
/// @file
/// The projection and binning of segment_bins in AVX-512F, sixteen segments of a strand at a time:
/// the strand's points loaded whole and split into ends by permutations, both ends projected
/// (light_space::project, product by product as it rounds them), the near and far planes and the
/// guard band checked, the ends snapped, the records written sixteen at a time, and the segment
/// counted in its tile when it lies in one tile, or (on a rebuild) in two side by side. Segments that
/// need clipping, or that reach more tiles, go through the scalar code, lane by lane, in order; so
/// every segment, count and first tile is the scalar one (tests/test_tile_walk.cpp checks it). segment_bins
/// includes this header before its class and calls strand_projection::project.

#include <hairshadow/core/light.hpp>
#include <hairshadow/raster/depth_extent.hpp>
#include <hairshadow/raster/instruction_set.hpp>
#include <hairshadow/raster/detail/prepared_segment.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <type_traits>

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

/// (clip / w + 1) half_res, light_space::project's window coordinate; without the division where the
/// light is `affine` (w is 1).
HAIRSHADOW_AVX512_TARGET inline __m512 window_coordinate(__m512 clip, __m512 w, bool affine, __m512 half_res) noexcept {
    return _mm512_mul_ps(_mm512_add_ps(affine ? clip : _mm512_div_ps(clip, w), _mm512_set1_ps(1.0f)), half_res);
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

/// Sixteen lanes' `component` (0: x, 1: y, 2: z) of points[l + shift], from four vectors holding the
/// 64 floats from points[0].x on: two permutations and a blend in place of a gather, which costs
/// more.
HAIRSHADOW_AVX512_TARGET inline __m512 point_component(const __m512 (&v)[4], int component, int shift) noexcept {
    __m512i index = _mm512_set_epi32(45, 42, 39, 36, 33, 30, 27, 24, 21, 18, 15, 12, 9, 6, 3, 0);
    index = _mm512_add_epi32(index, _mm512_set1_epi32(3 * shift + component));
    const __mmask16 second_half = _mm512_cmpge_epi32_mask(index, _mm512_set1_epi32(32));
    return _mm512_mask_blend_ps(second_half, _mm512_permutex2var_ps(v[0], index, v[1]), _mm512_permutex2var_ps(v[2], index, v[3]));
}

/// Where a record's field comes from when sixteen segments' fields (six vectors, a lane each) are
/// interleaved into sixteen 24-byte segment_geometry records, as six vectors of sixteen 32-bit words:
/// output word j of vector v is field (16 v + j) % 6 of lane (16 v + j) / 6, always in the same
/// half of the lanes (v < 3: lanes 0-7). pair_index picks it from the half's fields 0-3, held as
/// [field 0 | field 1] and [field 2 | field 3] (eight lanes each); last_index from [field 4 | field 5].
struct record_layout {
    std::array<std::array<std::int32_t, 16>, 6> pair_index{}, last_index{};
    std::array<std::uint16_t, 6> last_fields{};
    constexpr record_layout() {
        for (int v = 0; v < 6; ++v)
            for (int j = 0; j < 16; ++j) {
                const int k = 16 * v + j, field = k % 6, lane = k / 6 - 8 * (v / 3);
                if (field < 4) pair_index[std::size_t(v)][std::size_t(j)] = (field / 2) * 16 + (field % 2) * 8 + lane;
                else last_index[std::size_t(v)][std::size_t(j)] = (field - 4) * 8 + lane, last_fields[std::size_t(v)] |= std::uint16_t(1u << j);
            }
    }
};
inline constexpr record_layout record_layout_table{};

/// The records of the first `lanes` segments stored at `out`: six fields, a lane each, interleaved by
/// permutations (record_layout) and written whole, in place of a copy lane by lane.
HAIRSHADOW_AVX512_TARGET inline void store_records(segment_geometry* out, int lanes, const __m512i (&field)[6]) noexcept {
    static_assert(sizeof(segment_geometry) == 6 * sizeof(std::int32_t) && std::is_standard_layout_v<segment_geometry>);
    auto* words = reinterpret_cast<std::int32_t*>(out);
    const int total = 6 * lanes;
    // [field 0 | field 1], [field 2 | field 3], [field 4 | field 5] of each half's eight lanes.
    const __m512i pairs[2][3] = {{_mm512_shuffle_i64x2(field[0], field[1], 0x44), _mm512_shuffle_i64x2(field[2], field[3], 0x44),
                                  _mm512_shuffle_i64x2(field[4], field[5], 0x44)},
                                 {_mm512_shuffle_i64x2(field[0], field[1], 0xEE), _mm512_shuffle_i64x2(field[2], field[3], 0xEE),
                                  _mm512_shuffle_i64x2(field[4], field[5], 0xEE)}};
    for (int half = 0; half < 2; ++half) {
        const __m512i f01 = pairs[half][0], f23 = pairs[half][1], f45 = pairs[half][2];
        for (int v = 3 * half; v < 3 * half + 3 && 16 * v < total; ++v) {
            const auto u = std::size_t(v);
            __m512i words_v = _mm512_permutex2var_epi32(f01, _mm512_loadu_si512(record_layout_table.pair_index[u].data()), f23);
            words_v = _mm512_mask_permutexvar_epi32(words_v, record_layout_table.last_fields[u], _mm512_loadu_si512(record_layout_table.last_index[u].data()), f45);
            const int left = total - 16 * v;
            _mm512_mask_storeu_epi32(words + 16 * v, left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u), words_v);
        }
    }
}

/// The 1/w pairs of the first `lanes` segments stored at `out`, interleaved.
HAIRSHADOW_AVX512_TARGET inline void store_inv_w(std::array<float, 2>* out, int lanes, __m512 inv_w_a, __m512 inv_w_b) noexcept {
    auto* words = reinterpret_cast<float*>(out);
    for (int v = 0; v < 2 && 16 * v < 2 * lanes; ++v) {
        // Word j: field j % 2 of lane 8 v + j / 2.
        const __m512i index = _mm512_add_epi32(_mm512_set_epi32(23, 7, 22, 6, 21, 5, 20, 4, 19, 3, 18, 2, 17, 1, 16, 0), _mm512_set1_epi32(8 * v));
        const int left = 2 * lanes - 16 * v;
        _mm512_mask_storeu_ps(words + 16 * v, left >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u), _mm512_permutex2var_ps(inv_w_a, index, inv_w_b));
    }
}

/// count_tiles' bound for segments of one tile, a lane each: segment_fragment_bound, at most the
/// lines of fragment_lines_of in the tile. Within the guard band every difference fits in 32 bits.
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline __m512i one_tile_bounds(__m512i sax, __m512i say, __m512i sbx, __m512i sby, __m512i tx0,
                                                                              __m512i ty0, int tile_shift, int tile_size) noexcept {
    const __m512i one_i = _mm512_set1_epi32(1), zero_i = _mm512_setzero_si512();
    const __m512i dx = _mm512_abs_epi32(_mm512_sub_epi32(sbx, sax)), dy = _mm512_abs_epi32(_mm512_sub_epi32(sby, say));
    const __m512i most = _mm512_min_epi32(_mm512_add_epi32(_mm512_srai_epi32(_mm512_max_epi32(dx, dy), HAIRSHADOW_SUBPIXEL_BITS), _mm512_set1_epi32(2)),
                                          _mm512_set1_epi32(tile_size + 1));
    const __mmask16 x_major = _mm512_cmpge_epi32_mask(dx, dy);
    const __m512i lo = _mm512_mask_blend_epi32(x_major, _mm512_min_epi32(say, sby), _mm512_min_epi32(sax, sbx));
    const __m512i hi = _mm512_mask_blend_epi32(x_major, _mm512_max_epi32(say, sby), _mm512_max_epi32(sax, sbx));
    const __m512i first_line = _mm512_sub_epi32(_mm512_srai_epi32(lo, HAIRSHADOW_SUBPIXEL_BITS), one_i);
    const __m512i last_line = _mm512_add_epi32(_mm512_srai_epi32(hi, HAIRSHADOW_SUBPIXEL_BITS), one_i);
    const __m512i tile_line = _mm512_slli_epi32(_mm512_mask_blend_epi32(x_major, ty0, tx0), tile_shift);
    const __m512i tile_end = _mm512_add_epi32(tile_line, _mm512_set1_epi32(tile_size - 1));
    const __m512i in_tile = _mm512_add_epi32(_mm512_sub_epi32(_mm512_min_epi32(last_line, tile_end), _mm512_max_epi32(first_line, tile_line)), one_i);
    return _mm512_min_epi32(most, _mm512_max_epi32(in_tile, zero_i));
}

/// Calls add(tile, lanes) once for each tile that the lanes of `m` have in `tiles`, with how many lanes
/// have it.
template <class Add>
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline void for_each_tile_of(unsigned m, __m512i tiles, const std::int32_t* tile, Add&& add) noexcept {
    while (m != 0) {
        const std::int32_t first = tile[std::countr_zero(m)];
        const unsigned same = m & _mm512_cmpeq_epi32_mask(tiles, _mm512_set1_epi32(first));
        add(std::size_t(first), std::uint64_t(std::popcount(same)));
        m &= ~same;
    }
}

/// Counts the lanes of one tile (with their bounds, on a first build) and of two tiles side by side
/// (right) or one above the other (below) in their tiles (`tiles`, also stored at `tile`), a tile at a
/// time: a strand's sixteen segments mostly lie in one or two tiles, and an increment a lane made a
/// chain of dependent read-modify-writes of one count (a fifth of the projection's time).
HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE inline void count_lanes(std::uint64_t* counts, std::uint64_t* bounds, __m512i tiles, const std::int32_t* tile,
                                                                          const std::int32_t* bound, unsigned one_tile, unsigned right, unsigned below,
                                                                          std::size_t tiles_x) noexcept {
    if (bounds) {
        for (unsigned m = one_tile; m != 0; m &= m - 1) {
            const int l = std::countr_zero(m);
            ++counts[tile[l]];
            bounds[tile[l]] += std::uint64_t(bound[l]);
        }
    } else {
        for_each_tile_of(one_tile, tiles, tile, [&](std::size_t t, std::uint64_t k) HAIRSHADOW_ALWAYS_INLINE { counts[t] += k; });
    }
    for_each_tile_of(right, tiles, tile, [&](std::size_t t, std::uint64_t k) HAIRSHADOW_ALWAYS_INLINE { counts[t] += k, counts[t + 1] += k; });
    for_each_tile_of(below, tiles, tile, [&](std::size_t t, std::uint64_t k) HAIRSHADOW_ALWAYS_INLINE { counts[t] += k, counts[t + tiles_x] += k; });
}

/// project_and_bin's loop over one strand of n points, whose first segment is first_seg: sixteen
/// segments at a time. A template on the bins only so that this header comes before the class it
/// fills (segment_bins, whose friend it is), with no include loop.
struct strand_projection {
    template <class Bins>
    HAIRSHADOW_AVX512_TARGET static void project(Bins& bins, const glm::vec3* points, std::size_t n, std::size_t first_seg,
                                                                             std::uint64_t* counts, std::uint64_t* bounds, depth_extent& e,
                                                                             std::int64_t reach) {
        const light_space& ls = bins.light_;
        const auto vp_x = ls.row_coefficients(ls.view_projection(), 0), vp_y = ls.row_coefficients(ls.view_projection(), 1);
        const auto vp_w = ls.row_coefficients(ls.view_projection(), 3), view_z = ls.row_coefficients(ls.view(), 2);
        const __m512 half_res = _mm512_set1_ps(0.5f * float(bins.res_)), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
        const __m512 near_plane = _mm512_set1_ps(ls.near_plane()), far_plane = _mm512_set1_ps(ls.far_plane());
        const __m512 depth_span = _mm512_set1_ps(ls.far_plane() - ls.near_plane());
        const __m512 guard = _mm512_set1_ps(guard_band), two = _mm512_set1_ps(2.0f);
        const __m512i reach_v = _mm512_set1_epi32(std::int32_t(reach)), res_v = _mm512_set1_epi32(bins.res_), last_v = _mm512_set1_epi32(bins.res_ - 1);
        const int tile_shift = std::countr_zero(unsigned(bins.opt_.tile_size));
        const __m512i tiles_x = _mm512_set1_epi32(bins.tiles_x_), zero_i = _mm512_setzero_si512(), one_i = _mm512_set1_epi32(1);
        // An orthographic light's w is 1 wherever the point is finite (and NaN elsewhere, which fails
        // the w > 0 test): a division by it changes nothing, and is skipped. 1/w is kept only for a
        // perspective light (store).
        const bool affine = vp_w[0] == 0.0f && vp_w[1] == 0.0f && vp_w[2] == 0.0f && vp_w[3] == 1.0f;
        const bool keep_inv_w = !bins.inv_w_.empty();
        __m512 nearest = _mm512_set1_ps(e.nearest), furthest = _mm512_set1_ps(e.furthest);
        alignas(64) std::int32_t tile[16], bound[16];
        const __m512i and_right_v = _mm512_set1_epi32(std::int32_t(Bins::and_right)), and_below_v = _mm512_set1_epi32(std::int32_t(Bins::and_below));
        const __m512i no_tile_v = _mm512_set1_epi32(std::int32_t(Bins::no_tile));
        const std::size_t segments = n - 1;
        for (std::size_t base = 0; base < segments; base += 16) {
            const auto lanes = int(std::min<std::size_t>(16, segments - base));
            const auto valid = __mmask16((1u << lanes) - 1u);
            // Both ends of each segment, points base + l and base + l + 1: the strand's floats from
            // points[base] on, loaded whole (masked past its last point: a masked load does not fault).
            const float* from = &points[base].x;
            const int floats = 3 * (lanes + 1);
            __m512 raw[4];
            for (int k = 0; k < 4; ++k) {
                const int left = std::clamp(floats - 16 * k, 0, 16);
                raw[k] = _mm512_maskz_loadu_ps(left == 16 ? __mmask16(0xFFFF) : __mmask16((1u << left) - 1u), from + 16 * k);
            }
            const __m512 x0 = point_component(raw, 0, 0), y0 = point_component(raw, 1, 0), z0 = point_component(raw, 2, 0);
            const __m512 x1 = point_component(raw, 0, 1), y1 = point_component(raw, 1, 1), z1 = point_component(raw, 2, 1);
            const __m512 d0 = negate(project_row(view_z, x0, y0, z0)), d1 = negate(project_row(view_z, x1, y1, z1));
            // No clipping at the near and far planes (prepare_segment's tests, in its own arithmetic).
            auto simple = __mmask16(valid & _mm512_cmp_ps_mask(_mm512_sub_ps(d0, near_plane), zero, _CMP_GE_OQ) &
                               _mm512_cmp_ps_mask(_mm512_sub_ps(d1, near_plane), zero, _CMP_GE_OQ) &
                               _mm512_cmp_ps_mask(_mm512_sub_ps(far_plane, d0), zero, _CMP_GE_OQ) &
                               _mm512_cmp_ps_mask(_mm512_sub_ps(far_plane, d1), zero, _CMP_GE_OQ));
            const __m512 w0 = project_row(vp_w, x0, y0, z0), w1 = project_row(vp_w, x1, y1, z1);
            const __m512 wx0 = window_coordinate(project_row(vp_x, x0, y0, z0), w0, affine, half_res);
            const __m512 wy0 = window_coordinate(project_row(vp_y, x0, y0, z0), w0, affine, half_res);
            const __m512 wx1 = window_coordinate(project_row(vp_x, x1, y1, z1), w1, affine, half_res);
            const __m512 wy1 = window_coordinate(project_row(vp_y, x1, y1, z1), w1, affine, half_res);
            const __m512 dep0 = _mm512_div_ps(_mm512_sub_ps(d0, near_plane), depth_span), dep1 = _mm512_div_ps(_mm512_sub_ps(d1, near_plane), depth_span);
            // Inside the guard band, finite, in front of the light: prepare_segment's last test.
            simple = __mmask16(simple & within(wx0, guard) & within(wy0, guard) & within(wx1, guard) & within(wy1, guard) & within(dep0, two) &
                               within(dep1, two) & _mm512_cmp_ps_mask(w0, zero, _CMP_GT_OQ) & _mm512_cmp_ps_mask(w1, zero, _CMP_GT_OQ));
            const __m512i sax = snap16(wx0), say = snap16(wy0), sbx = snap16(wx1), sby = snap16(wy1);
            const std::size_t first = first_seg + base;
            // Every lane's record; the lanes left to the scalar code below are written again there.
            store_records(bins.segments_.data() + first, lanes, {sax, say, sbx, sby, _mm512_castps_si512(dep0), _mm512_castps_si512(dep1)});
            if (keep_inv_w) store_inv_w(bins.inv_w_.data() + first, lanes, _mm512_div_ps(one, w0), _mm512_div_ps(one, w1));
            // One tile, or two side by side, inside the map: counted here; anything else goes through the
            // scalar code.
            const __mmask16 empty = _mm512_cmpeq_epi32_mask(sax, sbx) & _mm512_cmpeq_epi32_mask(say, sby);
            const __m512i lo_x = _mm512_srai_epi32(_mm512_sub_epi32(_mm512_min_epi32(sax, sbx), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
            const __m512i hi_x = _mm512_srai_epi32(_mm512_add_epi32(_mm512_max_epi32(sax, sbx), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
            const __m512i lo_y = _mm512_srai_epi32(_mm512_sub_epi32(_mm512_min_epi32(say, sby), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
            const __m512i hi_y = _mm512_srai_epi32(_mm512_add_epi32(_mm512_max_epi32(say, sby), reach_v), HAIRSHADOW_SUBPIXEL_BITS);
            const __mmask16 in_map = _mm512_cmpge_epi32_mask(hi_x, zero_i) & _mm512_cmpge_epi32_mask(hi_y, zero_i) &
                                     _mm512_cmplt_epi32_mask(lo_x, res_v) & _mm512_cmplt_epi32_mask(lo_y, res_v);
            const __m512i tx0 = _mm512_srai_epi32(_mm512_max_epi32(lo_x, zero_i), tile_shift), tx1 = _mm512_srai_epi32(_mm512_min_epi32(hi_x, last_v), tile_shift);
            const __m512i ty0 = _mm512_srai_epi32(_mm512_max_epi32(lo_y, zero_i), tile_shift), ty1 = _mm512_srai_epi32(_mm512_min_epi32(hi_y, last_v), tile_shift);
            const __mmask16 drawn = simple & __mmask16(~empty) & in_map;
            const __mmask16 same_column = _mm512_cmpeq_epi32_mask(tx0, tx1), same_row = _mm512_cmpeq_epi32_mask(ty0, ty1);
            const __mmask16 one_tile = drawn & same_column & same_row;
            // A box of two tiles: visit_tiles visits both, and count_tiles flags the second (and_right,
            // and_below). Left to count_tiles on a first build, which also bounds the tiles' fragments.
            const __mmask16 right = bounds ? __mmask16(0) : drawn & same_row & _mm512_cmpeq_epi32_mask(tx1, _mm512_add_epi32(tx0, one_i));
            const __mmask16 below = bounds ? __mmask16(0) : drawn & same_column & _mm512_cmpeq_epi32_mask(ty1, _mm512_add_epi32(ty0, one_i));
            const __mmask16 dropped = simple & (empty | __mmask16(~in_map));
            const __m512i first_tiles = _mm512_add_epi32(_mm512_mullo_epi32(ty0, tiles_x), tx0);
            _mm512_store_si512(tile, first_tiles);
            __m512i entry = _mm512_mask_or_epi32(first_tiles, right, first_tiles, and_right_v);
            entry = _mm512_mask_or_epi32(entry, below, entry, and_below_v);
            _mm512_mask_storeu_epi32(bins.first_tile_.data() + first, valid, _mm512_mask_mov_epi32(entry, dropped, no_tile_v));
            if (bounds) _mm512_store_si512(bound, one_tile_bounds(sax, say, sbx, sby, tx0, ty0, tile_shift, bins.opt_.tile_size));
            nearest = _mm512_mask_min_ps(nearest, drawn, nearest, _mm512_min_ps(dep0, dep1)); // segment_bins::meets_map
            furthest = _mm512_mask_max_ps(furthest, drawn, furthest, _mm512_max_ps(dep0, dep1));
            count_lanes(counts, bounds, first_tiles, tile, bound, one_tile, right, below, std::size_t(bins.tiles_x_));
            // The rest, in order: clipped segments (prepared by the scalar code) and those of more tiles.
            for (unsigned m = valid & ~unsigned(one_tile | right | below | dropped); m != 0; m &= m - 1) {
                const auto i = base + std::size_t(std::countr_zero(m));
                bins.first_tile_[first_seg + i] = bins.prepare_and_count(points[i], points[i + 1], (simple >> (i - base)) & 1u, first_seg + i, reach, counts, bounds, e);
            }
        }
        e.nearest = std::min(e.nearest, _mm512_reduce_min_ps(nearest));
        e.furthest = std::max(e.furthest, _mm512_reduce_max_ps(furthest));
    }
};

} // namespace avx512

} // namespace hairshadow::detail
