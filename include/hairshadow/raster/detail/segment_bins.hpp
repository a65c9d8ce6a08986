#pragma once
/// @file
/// The first two steps of every CPU build: each segment of a model projected and snapped once, then
/// binned into the square tiles of the light's map that it may touch. Every tile's list is in segment
/// order, whatever the thread count, so a texel's fragments always come in segment order.

#include <hairshadow/config.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/detail/huge_pages.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/depth_extent.hpp>
#include <hairshadow/raster/instruction_set.hpp>
#include <hairshadow/raster/detail/prepared_segment.hpp>
#if HAIRSHADOW_AVX512_WALK
#include <hairshadow/raster/detail/segment_project_avx512.hpp>
#endif

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <vector>

namespace hairshadow::detail {

/// A model's segments prepared for one light and binned into tiles; keeps its memory between calls.
class segment_bins {
public:
    /// Projects, snaps and bins every segment of `model` for `light`'s map, in tiles of
    /// options.tile_size texels, and bounds each tile's fragments where `bound_tiles` (a first build,
    /// whose tile stores are still to be sized; a rebuild skips the work). Throws argument_error for
    /// bad options.
    HAIRSHADOW_DECL void prepare(const hair_model& model, const light_space& light, const raster_options& options, bool bound_tiles = true);

    int resolution() const noexcept { return res_; }
    const raster_options& options() const noexcept { return opt_; }
    const light_space& light() const noexcept { return light_; }
    std::size_t segment_count() const noexcept { return segments_.size(); }
    std::size_t tile_count() const noexcept { return std::size_t(tiles_x_) * std::size_t(tiles_x_); }
    /// Segment-tile pairs: how many times the tile passes set up a segment.
    std::size_t pair_count() const noexcept { return binned_.size(); }
    /// Tiles from the most segments to the fewest: handing out the largest first balances threads.
    const std::vector<std::uint32_t>& tiles_by_load() const noexcept { return by_load_; }
    std::size_t tile_load(std::size_t t) const noexcept { return std::size_t(tile_begin_[t + 1] - tile_begin_[t]); }
    /// At most this many fragments fall in tile t, for thin lines (0 for wide ones, which have no
    /// such bound, and where prepare was not asked for it): a thin line makes at most one fragment per column where it is x-major (per row
    /// where y-major), so each segment gives a tile at most its length in texels plus 2, and at most
    /// the number of those columns (rows) in the tile that its span reaches (segment_fragment_bound,
    /// count_tiles). Lets the tile stores be sized before any walk; tests check it holds.
    std::size_t tile_fragment_bound(std::size_t t) const noexcept { return bounded_ ? std::size_t(tile_bound_[t]) : 0; }
    /// The largest tile_fragment_bound of the map's tiles.
    std::size_t largest_tile_fragment_bound() const noexcept { return bounded_ ? std::size_t(largest_bound_) : 0; }

    /// The whole-map pre-pass: nearest and furthest end of every segment whose box meets the map
    /// (meets_map). Each fragment's depth lies between its segment's end depths, so this range holds
    /// every fragment's; it can be wider, by the parts of segments that leave the map or cross no
    /// texel centre. Nothing about it depends on the tile size.
    depth_extent extent() const noexcept { return extent_; }

    texel_rect tile_rect(std::size_t t) const noexcept {
        const int tile = opt_.tile_size;
        const int tx = int(t % std::size_t(tiles_x_)), ty = int(t / std::size_t(tiles_x_));
        return {tx * tile, ty * tile, std::min(res_, (tx + 1) * tile), std::min(res_, (ty + 1) * tile)};
    }

    /// The segments binned to tile t, in segment order.
    std::span<const std::uint32_t> tile_segments(std::size_t t) const noexcept {
        return {binned_.data() + tile_begin_[t], std::size_t(tile_begin_[t + 1] - tile_begin_[t])};
    }
    /// Segment i, prepared. 1/w is kept only for a perspective light: an orthographic one's is 1.
    prepared_segment segment(std::size_t i) const noexcept {
        const std::array<float, 2> inv_w = inv_w_.empty() ? std::array<float, 2>{1.0f, 1.0f} : inv_w_[i];
        return {segments_[i], inv_w[0], inv_w[1]};
    }
    /// The segments' records, segment after segment (segment() reads them), and their 1/w pairs (null
    /// for an orthographic light): for the vector walk's gathers.
    const segment_geometry* segment_data() const noexcept { return segments_.data(); }
    const std::array<float, 2>* inv_w_data() const noexcept { return inv_w_.empty() ? nullptr : inv_w_.data(); }
    /// Fetches segment i into the cache ahead of its use: both of its ends, since a quarter of the
    /// 24-byte records straddle two cache lines.
    void prefetch_segment(std::size_t i) const noexcept { prefetch_lines(&segments_[i], sizeof(segment_geometry)); }
    /// Fetches the cache lines of the `bytes` (at most a line's) from `at`: the first and the last.
    static void prefetch_lines(const void* at, std::size_t bytes) noexcept {
#if defined(__GNUC__)
        __builtin_prefetch(at);
        __builtin_prefetch(static_cast<const char*>(at) + bytes - 1);
#else
        (void)at, (void)bytes;
#endif
    }
    /// Every segment has the same thickness and opacity at both ends (uniform_attributes()).
    bool uniform_attributes() const noexcept { return attributes_.empty(); }
    /// A segment of the same alpha at every fragment: constant attributes (uniform_attributes()) and a
    /// footprint that does not change with depth, or a fixed alpha. Then its alpha is this shader's.
    segment_shader uniform_shader() const noexcept { return {light_, opt_, prepared_segment{{0, 0, 1, 0, 0.0f, 0.0f}, 1.0f, 1.0f}, uniform_}; }

    /// The shading of segment i's fragments.
    segment_shader shader(std::size_t i) const noexcept {
        return {light_, opt_, segment(i), attributes_.empty() ? uniform_ : attributes_[i]};
    }

    /// Calls visit(shader) for each of tile t's segments, in segment order.
    template <class Visit>
    HAIRSHADOW_ALWAYS_INLINE void for_each_segment(std::size_t t, Visit&& visit) const {
        constexpr std::uint64_t lookahead = 8; // a tile's segments lie scattered in memory: fetch ahead
        const std::uint64_t end = tile_begin_[t + 1];
        for (std::uint64_t i = tile_begin_[t]; i < end; ++i) {
#if defined(__GNUC__)
            if (i + lookahead < end) prefetch_segment(binned_[i + lookahead]);
#endif
            visit(shader(binned_[i]));
        }
    }

    /// Calls visit(shader, x, y, t, weight) for every fragment of tile t's segments, in segment order;
    /// thin lines pass t = -1 (shader.parameter(x, y) gives it, when needed) and weight 1.
    template <class Visit>
    HAIRSHADOW_ALWAYS_INLINE void for_each_fragment(std::size_t t, Visit&& visit) const {
        const texel_rect rect = tile_rect(t);
        for_each_segment(t, [&](const segment_shader& shading) HAIRSHADOW_ALWAYS_INLINE {
            const prepared_segment& s = shading.segment();
            if (opt_.wide_line_width > 0.0f)
                rasterize_wide_line(s, opt_.wide_line_width, rect, [&](int x, int y, float param, float weight) { visit(shading, x, y, param, weight); });
            else
                rasterize_line(s.a(), s.b(), rect, [&](int x, int y) HAIRSHADOW_ALWAYS_INLINE { visit(shading, x, y, -1.0f, 1.0f); });
        });
    }

    /// Bytes of working memory held.
    std::size_t memory_bytes() const noexcept {
        return segments_.capacity() * sizeof(segment_geometry) + inv_w_.capacity() * sizeof(inv_w_[0]) + attributes_.capacity() * sizeof(segment_attributes) +
               (first_segment_.capacity() + chunk_strand_.capacity()) * sizeof(std::size_t) + first_tile_.capacity() * sizeof(std::uint32_t) + (cursor_.capacity() + tile_begin_.capacity()) * sizeof(std::uint64_t) +
               (binned_.capacity() + by_load_.capacity()) * sizeof(std::uint32_t) + chunk_extent_.capacity() * sizeof(depth_extent) +
               (bound_.capacity() + tile_bound_.capacity()) * sizeof(std::uint64_t);
    }

private:
    /// Chunks of the segment range, counted and written apart (at most 64, and fewer where the tiles
    /// are so many that each chunk's count per tile would take more than 32 MiB together). The lists
    /// come out in segment order for any chunk count, so the result depends on neither it nor the
    /// threads.
    static std::size_t chunk_count(std::size_t tiles) noexcept { return std::clamp<std::size_t>((std::size_t(1) << 22) / std::max<std::size_t>(tiles, 1), 1, 64); }

    // Each chunk (a strand range of about equal segment count, so that nothing depends on the thread
    // count) runs two passes over its segments:
    // 1. project and snap each segment, strand by strand, and count it in the tiles it reaches, noting
    //    its first tile (while the segment is in registers: the segments are read from memory once,
    //    in the walk, and never re-read to bin them);
    // 2. once every chunk's counts are known, write each segment into its tiles' lists.
    // Per-segment thickness and opacity are kept only when the model has them per point; otherwise
    // every segment shares one pair.
    //
    // A segment's entry in first_tile_: its first tile in the low bits, and in the high ones which
    // others it reaches. The two-tile and 2x2 cases (the curly 1.5M model, 64-texel tiles, makes 1.24
    // segment-tile pairs a segment at 512x512, 1.80 at 2048x2048) are written from the entry alone;
    // only the rest re-read the segment, a cache miss each.
    static constexpr std::uint32_t no_tile = std::numeric_limits<std::uint32_t>::max();
    static constexpr std::uint32_t more_tiles = std::uint32_t(1) << 31; ///< others than the flags below say: visit_tiles tells
    static constexpr std::uint32_t and_right = std::uint32_t(1) << 30;  ///< the tile to the right too (and_below: the 2x2 block)
    static constexpr std::uint32_t and_below = std::uint32_t(1) << 29;  ///< the tile below too
    static constexpr std::uint32_t tile_bits = and_below - 1;
    /// How many segments ahead the writing pass prefetches a segment it will re-read.
    static constexpr std::size_t reread_ahead = 48;

    void project_and_bin(const hair_model& model, const light_space& light, int res) {
        const bool per_point = size_for(model, light, res);
        project_chunks(model, light, per_point);
        const std::uint64_t total = tile_offsets();
        if (total > std::numeric_limits<std::uint32_t>::max()) throw argument_error("more than 2^32 segment-tile pairs");
        write_bins(total);
        order_by_load();
    }

    /// Sizes every array for this model and resolution; whether segments have per-point thickness or opacity.
    bool size_for(const hair_model& model, const light_space& light, int res) {
        res_ = res;
        tiles_x_ = (res + opt_.tile_size - 1) / opt_.tile_size;
        tile_magic_ = (std::uint64_t(1) << 32) / std::uint64_t(opt_.tile_size) + 1;
        static_assert(HAIRSHADOW_MAX_RESOLUTION <= (1 << 16), "tile_of needs texel coordinates below 2^16");
        const std::size_t tiles = tile_count();
        if (tiles > tile_bits) throw argument_error("too many tiles: use larger tiles");
        first_segment_.assign(model.strand_count() + 1, 0);
        for (std::size_t s = 0; s < model.strand_count(); ++s)
            first_segment_[s + 1] = first_segment_[s] + (model.strand_size(s) > 1 ? model.strand_size(s) - 1 : 0);
        const std::size_t count = first_segment_.back();
        if (count > std::numeric_limits<std::uint32_t>::max()) throw argument_error("more than 2^32 segments");
        segments_.resize(count);
        inv_w_.resize(light.perspective() ? count : 0);
        first_tile_.resize(count);
        const bool per_point = !model.thickness.empty() || !model.transparency.empty();
        const float t = model.default_thickness, o = 1.0f - model.default_transparency;
        uniform_ = {t, t, o, o};
        attributes_.resize(per_point ? count : 0);
        // Chunk c: the strands whose first segment lies in [c count / chunks, (c + 1) count / chunks).
        const std::size_t chunks = chunk_count(tiles);
        chunk_strand_.resize(chunks + 1);
        for (std::size_t c = 0; c <= chunks; ++c)
            chunk_strand_[c] = std::size_t(std::lower_bound(first_segment_.begin(), first_segment_.end() - 1, c * count / chunks) - first_segment_.begin());
        chunk_strand_[chunks] = model.strand_count();
        cursor_.assign(chunks * tiles, 0);
        bound_.assign(bounded_ ? chunks * tiles : 0, 0);
        chunk_extent_.assign(chunks, depth_extent{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()});
        return per_point;
    }

    /// Projects each chunk's strands (in parallel, a chunk a task), counting each chunk's segments in
    /// each tile, and the chunk's depth extent; then the whole extent.
    void project_chunks(const hair_model& model, const light_space& light, bool per_point) {
        const std::size_t tiles = tile_count(), chunks = chunk_strand_.size() - 1;
        const auto reach = this->reach();
        // The vector projection covers segments of one thickness and opacity, in tiles whose side is
        // a power of two.
        const bool vector = resolve(opt_.instructions) == instruction_set::avx512 && !per_point && std::has_single_bit(unsigned(opt_.tile_size));
        (void)vector;
        parallel_for(chunks, opt_.exec, [&](std::size_t c) {
            // Raw pointers: stores through a member vector would make the compiler reload its data pointer.
            segment_geometry* out = segments_.data();
            std::array<float, 2>* out_inv_w = inv_w_.empty() ? nullptr : inv_w_.data();
            std::uint32_t* first_tile = first_tile_.data();
            segment_attributes* out_attributes = per_point ? attributes_.data() : nullptr;
            std::uint64_t* counts = cursor_.data() + c * tiles;
            std::uint64_t* bounds = bounded_ ? bound_.data() + c * tiles : nullptr;
            const segment_attributes uniform = uniform_;
            depth_extent e = chunk_extent_[c];
            for (std::size_t strand = chunk_strand_[c]; strand < chunk_strand_[c + 1]; ++strand) {
                const std::size_t p0 = model.strand_offsets[strand], n = model.strand_size(strand);
                if (n < 2) continue;
                const glm::vec3* points = model.points.data() + p0;
#if HAIRSHADOW_AVX512_WALK
                if (vector) {
                    avx512::strand_projection::project(*this, points, n, first_segment_[strand], counts, bounds, e, reach);
                    continue;
                }
#endif
                projected_point from = project_point(light, points[0]);
                for (std::size_t i = 0; i + 1 < n; ++i) {
                    const projected_point to = project_point(light, points[i + 1]); // each point projected once
                    const std::size_t seg = first_segment_[strand] + i, p = p0 + i;
                    segment_attributes at = uniform;
                    if (out_attributes)
                        at = {model.thickness_at(p), model.thickness_at(p + 1), 1.0f - model.transparency_at(p), 1.0f - model.transparency_at(p + 1)};
                    prepared_segment s;
                    prepare_segment(light, points[i], points[i + 1], from, to, at, s);
                    out[seg] = s;
                    if (out_inv_w) out_inv_w[seg] = {s.inv_w_a, s.inv_w_b};
                    if (out_attributes) out_attributes[seg] = at;
                    from = to;
                    first_tile[seg] = count_tiles(s, reach, counts, bounds, e);
                }
            }
            chunk_extent_[c] = e;
        }, 1);
        extent_ = {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
        for (const auto& e : chunk_extent_) extent_.nearest = std::min(extent_.nearest, e.nearest), extent_.furthest = std::max(extent_.furthest, e.furthest);
        if (!(extent_.nearest <= extent_.furthest)) extent_ = {}; // nothing reaches the map: {0, 0}, as extent_of an empty buffer
    }

    /// Each chunk's cursor in each tile, tile by tile then chunk by chunk (so every tile's segments
    /// keep their order); the pairs in all.
    std::uint64_t tile_offsets() {
        const std::size_t tiles = tile_count(), chunks = chunk_strand_.size() - 1;
        tile_begin_.resize(tiles + 1);
        tile_bound_.assign(bounded_ ? tiles : 0, 0);
        std::uint64_t total = 0;
        largest_bound_ = 0;
        for (std::size_t tile = 0; tile < tiles; ++tile) {
            tile_begin_[tile] = total;
            for (std::size_t c = 0; c < chunks; ++c) {
                const std::uint64_t k = cursor_[c * tiles + tile];
                cursor_[c * tiles + tile] = total;
                total += k;
                if (bounded_) tile_bound_[tile] += bound_[c * tiles + tile];
            }
            if (bounded_) largest_bound_ = std::max(largest_bound_, tile_bound_[tile]);
        }
        tile_begin_[tiles] = total;
        return total;
    }

    /// Writes each segment into the bins of the tiles it reaches, each chunk from its cursors.
    void write_bins(std::uint64_t total) {
        const std::size_t tiles = tile_count(), chunks = chunk_strand_.size() - 1;
        const auto reach = this->reach();
        binned_.resize(total);
        parallel_for(chunks, opt_.exec, [&](std::size_t c) {
            std::uint64_t* cursor = cursor_.data() + c * tiles;
            std::uint32_t* binned = binned_.data();
            const std::uint32_t* first_tile = first_tile_.data();
            const segment_geometry* segments = segments_.data();
            const std::size_t end = first_segment_[chunk_strand_[c + 1]];
            // A run of segments in one tile (a strand's, mostly) keeps that tile's cursor in a register:
            // through memory, each write waited on the last one's increment of the same cursor.
            std::uint32_t run_tile = no_tile;
            std::uint64_t run_at = 0;
            const auto end_run = [&]() HAIRSHADOW_ALWAYS_INLINE {
                if (run_tile != no_tile) cursor[run_tile] = run_at;
                run_tile = no_tile;
            };
            for (std::size_t seg = first_segment_[chunk_strand_[c]]; seg < end; ++seg) {
                // The segments re-read below are a few in a hundred, too sparse for the hardware's
                // prefetcher: each would miss the cache. Fetch the one
                // `reread_ahead` on, if it is one; else the entry at hand, already cached (a choice
                // without a branch).
                if (seg + reread_ahead < end) {
                    const std::size_t ahead = seg + reread_ahead;
                    prefetch_lines((first_tile[ahead] & more_tiles) ? static_cast<const void*>(segments + ahead) : first_tile + seg, sizeof(segment_geometry));
                }
                const std::uint32_t first = first_tile[seg];
                if (first == no_tile) continue;
                if ((first & ~tile_bits) == 0) { // one tile
                    if (first != run_tile) end_run(), run_tile = first, run_at = cursor[first];
                    binned[run_at++] = std::uint32_t(seg);
                    continue;
                }
                end_run();
                const auto put = [&](std::size_t tile) HAIRSHADOW_ALWAYS_INLINE { binned[cursor[tile]++] = std::uint32_t(seg); };
                if (first & more_tiles) {
                    visit_tiles(segments_[seg], reach, [&](std::size_t tile, int, int) HAIRSHADOW_ALWAYS_INLINE { put(tile); });
                    continue;
                }
                const std::size_t tile = first & tile_bits, below = tile + std::size_t(tiles_x_);
                put(tile);
                if (first & and_right) put(tile + 1);
                if (first & and_below) put(below);
                if ((first & and_right) && (first & and_below)) put(below + 1);
            }
            end_run();
        });
    }

    /// The tiles, the most loaded first.
    void order_by_load() {
        const std::size_t tiles = tile_count();
        by_load_.resize(tiles);
        std::iota(by_load_.begin(), by_load_.end(), 0u);
        // The most loaded first, ties in tile order: stable_sort's order, without the buffer it
        // allocates on every call (a rebuild allocates nothing).
        std::sort(by_load_.begin(), by_load_.end(), [&](std::uint32_t a, std::uint32_t b) {
            const auto la = tile_load(a), lb = tile_load(b);
            return la != lb ? la > lb : a < b;
        });
    }


    /// Counts segment s in each tile it reaches and returns its entry in first_tile_ (its first tile
    /// and which others it reaches), or no_tile; widens e by its ends when its box meets the map.
    /// Adds its bound on each tile's fragments to `bounds`, unless null.
    HAIRSHADOW_ALWAYS_INLINE std::uint32_t count_tiles(const segment_geometry& s, std::int64_t reach, std::uint64_t* counts, std::uint64_t* bounds,
                                                       depth_extent& e) const noexcept {
        if (s.empty() || !meets_map(s, reach)) return no_tile;
        e.nearest = std::min({e.nearest, s.depth_a, s.depth_b});
        e.furthest = std::max({e.furthest, s.depth_a, s.depth_b});
        std::size_t visited = 0;
        std::array<std::size_t, 4> tiles{}; // the first four it reaches
        const fragment_lines lines = bounds ? fragment_lines_of(s, opt_.tile_size) : fragment_lines{}; // a rebuild bounds nothing
        visit_tiles(s, reach, [&](std::size_t tile, int tx, int ty) HAIRSHADOW_ALWAYS_INLINE {
            ++counts[tile];
            if (bounds) { // at most one fragment in each of those lines that lies in the tile
                const std::int64_t tile_line = std::int64_t(lines.x_major ? tx : ty) * opt_.tile_size;
                const std::int64_t in_tile = std::min(lines.last, tile_line + opt_.tile_size - 1) - std::max(lines.first, tile_line) + 1;
                bounds[tile] += std::min(lines.bound, std::uint64_t(std::max<std::int64_t>(in_tile, 0)));
            }
            if (visited < tiles.size()) tiles[visited] = tile;
            ++visited;
        });
        if (visited == 0) return no_tile;
        // Tiles are visited row by row, left to right, so a set the flags describe comes in this order.
        const std::size_t first = tiles[0], right = first + 1, below = first + std::size_t(tiles_x_);
        const auto entry = std::uint32_t(first);
        if (visited == 1) return entry;
        if (visited == 2 && tiles[1] == right) return entry | and_right;
        if (visited == 2 && tiles[1] == below) return entry | and_below;
        if (visited == 4 && tiles[1] == right && tiles[2] == below && tiles[3] == below + 1) return entry | and_right | and_below;
        return std::uint32_t(first) | more_tiles;
    }

    /// Keeps prepared segment s as segment seg (its 1/w only for a perspective light).
    void store(std::size_t seg, const prepared_segment& s) noexcept {
        segments_[seg] = s;
        if (!inv_w_.empty()) inv_w_[seg] = {s.inv_w_a, s.inv_w_b};
    }

    /// One segment of project_strand_avx512 that the vector code leaves alone, prepared and counted
    /// by the scalar code, compiled apart from the AVX-512 function: inlined there, the compiler could
    /// fuse its multiplications and additions and prepare or bin the segment differently.
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    std::uint32_t prepare_and_count(const glm::vec3& p0, const glm::vec3& p1, bool prepared, std::size_t seg, std::int64_t reach,
                                    std::uint64_t* counts, std::uint64_t* bounds, depth_extent& e) {
        if (!prepared) {
            segment_attributes at = uniform_;
            prepared_segment s;
            prepare_segment(light_, p0, p1, project_point(light_, p0), project_point(light_, p1), at, s);
            store(seg, s);
        }
        return count_tiles(segments_[seg], reach, counts, bounds, e);
    }

#if HAIRSHADOW_AVX512_WALK
#if HAIRSHADOW_AVX512_WALK
    friend struct avx512::strand_projection; ///< project_and_bin's loop over a strand, sixteen segments at a time
#endif
#endif

    /// Texels around a segment that it may touch, in sub-pixel units.
    std::int64_t reach() const noexcept { return std::int64_t(std::ceil((1.0 + 0.5 * double(opt_.wide_line_width)) * double(subpixel_scale))); }

    /// texel / tile_size for a texel of the map, by a multiplication: q = (texel m) >> 32 with
    /// m = floor(2^32 / tile) + 1 is exact for texel < 2^16 and tile <= 2^10 (the error, texel (m tile -
    /// 2^32) / (tile 2^32) < 2^-16, stays below the gap 1 / tile to the next integer). It spares the
    /// binning a division per end per segment.
    HAIRSHADOW_ALWAYS_INLINE int tile_of(std::int64_t texel) const noexcept { return int((std::uint64_t(texel) * tile_magic_) >> 32); }

    /// Does the segment's bounding box, widened by `reach`, meet the map? The whole-map extent counts
    /// the segments that do, whatever the tiles.
    HAIRSHADOW_ALWAYS_INLINE bool meets_map(const segment_geometry& s, std::int64_t reach) const noexcept {
        const std::int64_t hi_x = (std::max<std::int64_t>(s.ax, s.bx) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t hi_y = (std::max<std::int64_t>(s.ay, s.by) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t lo_x = (std::min<std::int64_t>(s.ax, s.bx) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t lo_y = (std::min<std::int64_t>(s.ay, s.by) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        return !(hi_x < 0 || hi_y < 0 || lo_x >= res_ || lo_y >= res_);
    }

    /// Calls visit(tile, tx, ty) (the tile's index and column and row of tiles) for each tile within `reach` (sub-pixel units) of the segment; a long diagonal
    /// segment visits O(its length) tiles rather than its whole bounding box. Integer arithmetic only,
    /// so that the counting and the writing pass, wherever the compiler puts them, visit the same tiles.
    template <class Visit>
    HAIRSHADOW_ALWAYS_INLINE void visit_tiles(const segment_geometry& s, std::int64_t reach, Visit&& visit) const {
        if (!meets_map(s, reach)) return;
        // Texel bounds of the segment plus its reach; arithmetic shifts floor negative values.
        const std::int64_t lo_x = (std::min<std::int64_t>(s.ax, s.bx) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t hi_x = (std::max<std::int64_t>(s.ax, s.bx) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t lo_y = (std::min<std::int64_t>(s.ay, s.by) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t hi_y = (std::max<std::int64_t>(s.ay, s.by) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const int tx0 = tile_of(std::max<std::int64_t>(lo_x, 0)), tx1 = tile_of(std::min<std::int64_t>(hi_x, res_ - 1));
        const int ty0 = tile_of(std::max<std::int64_t>(lo_y, 0)), ty1 = tile_of(std::min<std::int64_t>(hi_y, res_ - 1));
        if (ty0 == ty1 || tx0 == tx1) { // most hair segments: one row or column of tiles, as the box says
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) visit(std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx), tx, ty);
            return;
        }
        // A segment across several rows and columns: per row of tiles, only the columns that the
        // segment's piece in that row's band (widened by reach) spans, floored and ceiled outwards.
        const std::int64_t side = std::int64_t(opt_.tile_size) * subpixel_scale;
        const std::int64_t dy = std::int64_t(s.by) - s.ay, dx = std::int64_t(s.bx) - s.ax;
        const std::int64_t y_lo = std::min<std::int64_t>(s.ay, s.by), y_hi = std::max<std::int64_t>(s.ay, s.by);
        auto x_at = [&](std::int64_t y, bool up) { // x on the segment at height y, rounded down or up
            if (dy == 0) return up ? std::max<std::int64_t>(s.ax, s.bx) : std::min<std::int64_t>(s.ax, s.bx); // a level segment whose reach spans rows
            const std::int64_t num = (y - s.ay) * dx * (dy > 0 ? 1 : -1), den = dy > 0 ? dy : -dy;
            const std::int64_t q = floor_div(num, den);
            return s.ax + q + (up && q * den != num ? 1 : 0);
        };
        for (int ty = ty0; ty <= ty1; ++ty) {
            const std::int64_t band_lo = std::max(std::int64_t(ty) * side - reach, y_lo), band_hi = std::min(std::int64_t(ty + 1) * side + reach, y_hi);
            if (band_lo > band_hi) continue;
            const std::int64_t x_lo = std::min(x_at(band_lo, false), x_at(band_hi, false)) - reach;
            const std::int64_t x_hi = std::max(x_at(band_lo, true), x_at(band_hi, true)) + reach;
            const int c0 = int(std::max<std::int64_t>(tx0, floor_div(x_lo, side))), c1 = int(std::min<std::int64_t>(tx1, floor_div(x_hi, side)));
            for (int tx = c0; tx <= c1; ++tx) visit(std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx), tx, ty);
        }
    }

    raster_options opt_;
    light_space light_;
    int res_ = 0, tiles_x_ = 0;
    std::uint64_t tile_magic_ = 0;
    std::vector<segment_geometry, huge_page_allocator<segment_geometry>> segments_;
    std::vector<std::array<float, 2>, huge_page_allocator<std::array<float, 2>>> inv_w_; ///< per segment, for a perspective light only
    std::vector<std::uint64_t> bound_;      ///< per chunk and tile: the sum of its segments' segment_fragment_bound
    std::vector<std::uint64_t> tile_bound_; ///< per tile: the chunks' sums
    std::uint64_t largest_bound_ = 0;
    bool bounded_ = false; ///< prepare was asked for the tiles' bounds
    std::vector<segment_attributes> attributes_; ///< per segment, only when the model has per-point thickness or transparency
    segment_attributes uniform_{};
    std::vector<std::size_t> first_segment_, chunk_strand_;
    std::vector<std::uint32_t, huge_page_allocator<std::uint32_t>> first_tile_; ///< per segment: its first tile, no_tile, or with more_tiles set
    std::vector<std::uint64_t> cursor_, tile_begin_;
    std::vector<std::uint32_t, huge_page_allocator<std::uint32_t>> binned_;
    std::vector<std::uint32_t> by_load_;
    std::vector<depth_extent> chunk_extent_;
    depth_extent extent_{};
};

#if HAIRSHADOW_KERNEL_BODIES
HAIRSHADOW_DECL void segment_bins::prepare(const hair_model& model, const light_space& light, const raster_options& options, bool bound_tiles) {
    options.check();
    opt_ = options;
    light_ = light;
    bounded_ = bound_tiles && opt_.wide_line_width == 0.0f;
    project_and_bin(model, light, light.resolution());
}
#endif
} // namespace hairshadow::detail
