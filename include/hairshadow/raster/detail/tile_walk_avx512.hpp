#pragma once
/// @file
/// The tiled build's line walk in AVX-512F, chosen at run time (raster_options::instructions), with
/// the kernels of raster/detail/tile_walk_lanes_avx512.hpp. Sixteen segments of a tile are set up at once,
/// one per lane, and walked in lockstep where they are short, one at a time sixteen texels a step where
/// they are long; the fragments are stored segment after segment (the scalar walk's store, bit for
/// bit), or, where the build allows any order, as each step gives them. tile_fragments::gather calls
/// it; the walk is a template on the tile only so that this header comes before the class it fills
/// (tile_fragments, whose friend it is), with no include loop.

#include <hairshadow/raster/instruction_set.hpp>
#include <hairshadow/raster/detail/segment_bins.hpp>
#include <hairshadow/raster/detail/tile_walk_lanes_avx512.hpp>

#include <algorithm>
#include <cstdint>
#include <span>

namespace hairshadow::detail::avx512 {

/// The walk of one tile into a tile_fragments' store.
struct tile_walk {

    /// Walks tile t, whose every fragment has one optical depth (simd_tile(): the store keeps it once,
    /// not per fragment). A batch of sixteen
    /// segments of at most sixteen texels in the tile (most of them, at 512x512 in tiles of 64) is walked
    /// in lockstep, one segment per lane, and a transpose turns the steps into each segment's fragments;
    /// other segments are walked one at a time, sixteen texels per step. Either way the fragments are
    /// stored segment after segment, in the tile's order: the scalar walk's store, bit for bit.
    template <class Tile>
    HAIRSHADOW_AVX512_TARGET static void walk_avx512(Tile& store, const segment_bins& bins, std::size_t t) {
        constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
        const int w = store.width_;
        const std::int64_t ox = std::int64_t(store.rect_.x0) << bits, oy = std::int64_t(store.rect_.y0) << bits;
        const auto list = bins.tile_segments(t);
        const __m512i none = _mm512_set1_epi32(std::int32_t(no_texel)), sixteen = _mm512_set1_epi32(16);
        // Sixteen records gathered at once, by 32-bit word offsets (six words a record).
        const bool gathered = bins.segment_count() < (std::size_t(1) << 28);
        batch b;
        __m512i where[16], depth[16]; // a block of lockstep steps, then of segments
        typename Tile::store_cursor c = store.cursor();
        for (std::size_t base = 0; base < list.size(); base += 16) {
            const int lanes = int(std::min<std::size_t>(16, list.size() - base));
            prefetch_next_batch(bins, list, base); // fetched while this one is walked
            if (gathered) gather_batch(b, bins, list.data() + base, lanes, std::int32_t(ox), std::int32_t(oy));
            else fill_batch(b, bins, list.data() + base, lanes, ox, oy);
            set_up(b, w, store.rect_.y1 - store.rect_.y0);
            const __m512i counts = _mm512_load_si512(b.count);
            auto side_by_side = __mmask16(b.simd & _mm512_cmple_epi32_mask(counts, sixteen));
            const int steps = side_by_side ? _mm512_mask_reduce_max_epi32(side_by_side, counts) : 0;
            // Every lockstep segment pays for the longest one's steps, and the batch for two transposes:
            // unless most lanes are short (all sixteen for sixteen steps, twelve for eight), they walk
            // alone. The rule was chosen by measurement (BENCHMARKS.md, "Full rebuilds", the entry on
            // the lockstep walk); it chooses a path, never a fragment.
            if (2 * __builtin_popcount(side_by_side) < steps + 16) side_by_side = 0;
            __mmask16 start_in_row = 0;
            if (side_by_side) {
                walk_lockstep(b, steps, w, where, depth);
                start_in_row = place_starts(b, side_by_side, w, where, depth);
                transpose(where);
                transpose(depth);
            }
            for (int l = 0; l < lanes; ++l) {
                if (!((b.simd >> l) & 1u)) {
                    store.n_ = c.n;
                    store.walk_segment_apart(bins, list[base + std::size_t(l)]);
                    c = store.cursor();
                    continue;
                }
                if (!((side_by_side >> l) & 1u)) {
                    walk_lane_avx512(store, c, b, l);
                    continue;
                }
                store.make_room(c, std::size_t(b.count[l]) + 1);
                store_kept(c, _mm512_cmpneq_epi32_mask(where[l], none), where[l], _mm512_castsi512_ps(depth[l]), c.n + 16 <= c.end);
                if ((unsigned(b.start & ~start_in_row) >> l) & 1u) store_start(store, c, b, l);
            }
        }
        store.n_ = c.n;
    }

    /// The `lanes` of b (set up) walked side by side, enough steps for the longest, each step's
    /// fragments stored as they come; then their start fragments.
    template <class Tile>
    HAIRSHADOW_AVX512_TARGET static void walk_rows_avx512(Tile& store, typename Tile::store_cursor& c, const batch& b, __mmask16 lanes) {
        const __m512i counts = _mm512_load_si512(b.count), none = _mm512_set1_epi32(std::int32_t(no_texel));
        store.make_room(c, std::size_t(_mm512_mask_reduce_add_epi32(lanes, counts)) + std::size_t(__builtin_popcount(lanes)));
        const int steps = _mm512_mask_reduce_max_epi32(lanes, counts);
        lockstep walk(b, store.width_);
        for (int j = 0; j < steps; ++j) {
            __m512 depth;
            const __m512i texels = walk.step(j, depth);
            store_kept(c, __mmask16(lanes & _mm512_cmpneq_epi32_mask(texels, none)), texels, depth, c.n + 16 <= c.end);
        }
        const __m512i start = _mm512_add_epi32(_mm512_mullo_epi32(_mm512_load_si512(b.start_y), _mm512_set1_epi32(store.width_)), _mm512_load_si512(b.start_x));
        store_kept(c, __mmask16(lanes & b.start), start, _mm512_load_ps(b.start_depth), c.n + 16 <= c.end);
    }

    /// The tile's segments in `list` ordered by how many steps of the walk they take in it
    /// (major_steps::count), fewest first and in list order among equals (a stable counting sort): a
    /// batch of them then walks side by side with few idle lanes.
    template <class Tile>
    HAIRSHADOW_AVX512_TARGET static std::span<const std::uint32_t> by_steps(Tile& store, const segment_bins& bins, std::span<const std::uint32_t> list,
                                                                                           std::int32_t ox, std::int32_t oy) {
        const std::size_t n = list.size();
        const int h = store.rect_.y1 - store.rect_.y0, most = std::max(store.width_, h);
        if (store.sorted_.size() < n) store.reserve_segments(n + n / 2, most); // reserve_segments made room for the largest tile
        store.steps_of_.assign(std::size_t(most) + 2, 0);
        std::uint16_t* steps = store.steps_.data();
        // The records are first read here, from all over the map's: fetched four batches ahead, the
        // first four before the loop.
        constexpr std::size_t ahead = 64;
        for (std::size_t i = 0; i < std::min(ahead, n); ++i) bins.prefetch_segment(list[i]);
        for (std::size_t base = 0; base < n; base += 16) {
            const int lanes = int(std::min<std::size_t>(16, n - base));
            prefetch_next_batch(bins, list, base, ahead);
            const gathered_ends ends(bins, list.data() + base, lanes, ox, oy);
            const major_steps walk(ends.ax, ends.ay, ends.bx, ends.by, store.width_, h); // count in [0, most], whatever the ends
            _mm512_mask_cvtepi32_storeu_epi16(steps + base, __mmask16((1u << lanes) - 1u), walk.count);
        }
        std::uint32_t* first = store.steps_of_.data() + 1;
        for (std::size_t i = 0; i < n; ++i) ++first[steps[i]];
        for (std::size_t k = 1; k < store.steps_of_.size(); ++k) store.steps_of_[k] += store.steps_of_[k - 1];
        first = store.steps_of_.data();
        for (std::size_t i = 0; i < n; ++i) store.sorted_[first[steps[i]]++] = list[i];
        return {store.sorted_.data(), n};
    }

    /// Whether sorting tile t's segments by their steps (by_steps) saves more lockstep steps than it
    /// costs, judged from the tile's first `sample` segments: walked in list order, each batch takes
    /// as many steps as its longest lane; sorted, the lanes are nearly of one length, and a batch's
    /// steps are about its lanes' mean. Sorting costs a segment about half a lockstep step (one more
    /// gather of its record, and its place in the counting sort), so it pays where list order wastes
    /// more than that a segment: long segments cut short by the tile's edges (curly at 2048x2048), not
    /// short ones (curly at 512x512; BENCHMARKS.md, "Issue 43: the tiles sorted only where it pays").
    /// It chooses an order, never a fragment; segment_count() below 2^28 (gathered_ends).
    HAIRSHADOW_AVX512_TARGET static bool sorting_pays(const segment_bins& bins, std::size_t t) noexcept {
        constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
        constexpr std::size_t sample = 64;
        const texel_rect r = bins.tile_rect(t);
        const auto ox = std::int32_t(std::int64_t(r.x0) << bits), oy = std::int32_t(std::int64_t(r.y0) << bits);
        const auto list = bins.tile_segments(t);
        const std::size_t n = std::min(sample, list.size());
        // Lane steps spent idle: each lane of a batch waits for its longest lane.
        std::int64_t idle = 0;
        for (std::size_t base = 0; base < n; base += 16) {
            const int lanes = int(std::min<std::size_t>(16, n - base));
            const auto valid = __mmask16((1u << lanes) - 1u);
            const gathered_ends ends(bins, list.data() + base, lanes, ox, oy);
            const major_steps walk(ends.ax, ends.ay, ends.bx, ends.by, r.x1 - r.x0, r.y1 - r.y0); // count in [0, most], whatever the ends
            idle += std::int64_t(lanes) * _mm512_mask_reduce_max_epi32(valid, walk.count) - _mm512_mask_reduce_add_epi32(valid, walk.count);
        }
        // Wasted lockstep steps a segment, idle / 16 / n, above one half.
        return 2 * idle > 16 * std::int64_t(n);
    }

    /// Walks tile t, whose every fragment has one optical depth, into the store in an order of its
    /// own (fragment_order::any), the same fragments as walk_avx512: its segments in list order, or
    /// sorted by their steps in the tile (by_steps) where that pays (sorting_pays), walked sixteen at
    /// a time side by side, each step's fragments stored as they come, with no transpose back to
    /// segment order. A tile of one batch is walked in segment order.
    template <class Tile>
    HAIRSHADOW_AVX512_TARGET static void walk_any_order_avx512(Tile& store, const segment_bins& bins, std::size_t t) {
        constexpr int bits = HAIRSHADOW_SUBPIXEL_BITS;
        const int w = store.width_, h = store.rect_.y1 - store.rect_.y0;
        const auto ox = std::int32_t(std::int64_t(store.rect_.x0) << bits), oy = std::int32_t(std::int64_t(store.rect_.y0) << bits);
        const auto tile_list = bins.tile_segments(t);
        if (tile_list.size() <= 16) return walk_avx512(store, bins, t);
        const auto list = sorting_pays(bins, t) ? by_steps(store, bins, tile_list, ox, oy) : tile_list;
        batch b;
        typename Tile::store_cursor c = store.cursor();
        for (std::size_t base = 0; base < list.size(); base += 16) {
            const int lanes = int(std::min<std::size_t>(16, list.size() - base));
            // Fetched one batch ahead: in list order, where the walk reads most of them first (past the
            // sample sorting_pays read); sorted, after by_steps read them in list order, when a dense
            // tile's are past the second-level cache.
            prefetch_next_batch(bins, list, base);
            gather_batch(b, bins, list.data() + base, lanes, ox, oy);
            set_up(b, w, h);
            if (b.simd) walk_rows_avx512(store, c, b, b.simd);
            for (int l = 0; l < lanes; ++l)
                if (!((b.simd >> l) & 1u)) {
                    store.n_ = c.n;
                    store.walk_segment_apart(bins, list[base + std::size_t(l)]);
                    c = store.cursor();
                }
        }
        store.n_ = c.n;
    }

    /// Stores the `keep` lanes of texels and depths at c.n, in lane order, and advances it. Whole vectors,
    /// compressed in registers, where `whole` says 16 slots past c.n are there (a compress straight to
    /// memory is slower on some CPUs: BENCHMARKS.md, "Full rebuilds", the entry on streamed tiles); near
    /// the store's end, compressed to memory, so that the store grows exactly as the scalar walk's does.
    template <class Cursor>
    HAIRSHADOW_AVX512_TARGET static void store_kept(Cursor& c, __mmask16 keep, __m512i texels, __m512 depths,
                                                                    bool whole) noexcept {
        if (whole) {
            _mm512_storeu_si512(c.where + c.n, _mm512_maskz_compress_epi32(keep, texels));
            _mm512_storeu_ps(c.depth + c.n, _mm512_maskz_compress_ps(keep, depths));
        } else {
            _mm512_mask_compressstoreu_epi32(c.where + c.n, keep, texels);
            _mm512_mask_compressstoreu_ps(c.depth + c.n, keep, depths);
        }
        c.n += std::size_t(__builtin_popcount(keep));
    }

    /// The start fragment of lane l, as walk_line emits it, after the walk; stored always and kept when
    /// there is one, since whether there is one is anybody's guess.
    template <class Tile>
    HAIRSHADOW_AVX512_TARGET static void store_start(Tile& store, typename Tile::store_cursor& c, const batch& b, int l) noexcept {
        c.where[c.n] = std::uint32_t(b.start_y[l] * store.width_ + b.start_x[l]);
        c.depth[c.n] = b.start_depth[l];
        c.n += (b.start >> l) & 1u;
    }

    /// Lane l of b walked alone, sixteen texels per step: for segments of more than sixteen texels in the
    /// tile, and for every segment of a batch that does not walk in lockstep.
    template <class Tile>
    HAIRSHADOW_AVX512_TARGET HAIRSHADOW_ALWAYS_INLINE static void walk_lane_avx512(Tile& store, typename Tile::store_cursor& c, const batch& b, int l) {
        const int w = store.width_;
        const __m512i iota = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
        const __m512i none = _mm512_set1_epi32(std::int32_t(no_texel));
        const int count = b.count[l];
        store.make_room(c, std::size_t(count) + 1);
        const bool whole_vectors = c.n + std::size_t(count) + 16 <= c.end; // store_kept
        const __mmask16 along_x = (b.x_major >> l) & 1u ? __mmask16(0xFFFF) : __mmask16(0);
        const __mmask16 tie = (b.tie >> l) & 1u ? __mmask16(0xFFFF) : __mmask16(0);
        const __m512i m_begin = _mm512_set1_epi32(b.m_begin[l]), counts = _mm512_set1_epi32(count);
        const __m512i end_major = _mm512_set1_epi32(b.end_major[l]), end_minor = _mm512_set1_epi32(b.end_minor[l]);
        const __m512i minor_extent = _mm512_set1_epi32(b.minor_extent[l]), width = _mm512_set1_epi32(w);
        const __m512d num0 = _mm512_set1_pd(b.num0[l]), step = _mm512_set1_pd(b.step[l]), denom = _mm512_set1_pd(b.denom[l]);
        const __m512d inv_denom = _mm512_set1_pd(b.inv_denom[l]);
        const depth_along along = b.depths(l);
        // minor = floor(num / denom) for the first sixteen texels, as quotient q and remainder r
        // (exact_quotient); each next sixteen add sixteen steps' quotient and remainder, with a carry, as
        // walk_lockstep does one step.
        __m512d part[4];
        exact_quotient(_mm512_add_pd(num0, _mm512_mul_pd(low_pd(iota), step)), denom, inv_denom, part[0], part[1]);
        exact_quotient(_mm512_add_pd(num0, _mm512_mul_pd(high_pd(iota), step)), denom, inv_denom, part[2], part[3]);
        carried_quotient minor_at{integers_of(part[0], part[2]), integers_of(part[1], part[3]), _mm512_setzero_si512(), _mm512_setzero_si512(),
                                  _mm512_set1_epi32(std::int32_t(b.denom[l]))};
        if (count > 16) {
            exact_quotient(_mm512_mul_pd(_mm512_set1_pd(16.0), step), denom, inv_denom, part[0], part[1]);
            minor_at.q_step = _mm512_broadcast_i64x4(_mm512_cvttpd_epi32(part[0]));
            minor_at.r_step = _mm512_broadcast_i64x4(_mm512_cvttpd_epi32(part[1]));
        }
        for (int first = 0; first < count; first += 16) {
            const __m512i i = _mm512_add_epi32(iota, _mm512_set1_epi32(first));
            const __m512i minor = minor_at.minor(tie);
            minor_at.advance();
            __m512i x, y;
            const __m512i texels = step_texels(_mm512_add_epi32(i, m_begin), minor, _mm512_cmplt_epi32_mask(i, counts), along_x, end_major, end_minor,
                                               minor_extent, width, none, x, y);
            store_kept(c, _mm512_cmpneq_epi32_mask(texels, none), texels, along.at(x, y), whole_vectors);
        }
        store_start(store, c, b, l);
    }
};

} // namespace hairshadow::detail::avx512
