#pragma once
/// @file
/// A square map cut into square tiles, and which tiles a segment may touch: the geometry that the
/// binning's counting and writing passes share (raster/detail/segment_bins.hpp), in integers only, so
/// that both visit the same tiles wherever the compiler puts them.

#include <hairshadow/config.hpp>
#include <hairshadow/raster/line_rule.hpp>
#include <hairshadow/raster/detail/prepared_segment.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace hairshadow::detail {

/// A map of res x res texels in tiles of tile_size, tiles_x to a row, numbered row by row.
struct tile_grid {
    int res = 0, tile_size = 1, tiles_x = 0;
    std::uint64_t magic = 0; ///< tile_of's multiplier

    tile_grid() = default;
    tile_grid(int map_res, int tile) noexcept
        : res(map_res), tile_size(tile), tiles_x((map_res + tile - 1) / tile), magic((std::uint64_t(1) << 32) / std::uint64_t(tile) + 1) {
        static_assert(HAIRSHADOW_MAX_RESOLUTION <= (1 << 16), "tile_of needs texel coordinates below 2^16");
    }

    std::size_t tile_count() const noexcept { return std::size_t(tiles_x) * std::size_t(tiles_x); }

    /// Tile t's texels; the last row and column of tiles may be cut short by the map's edge.
    texel_rect tile_rect(std::size_t t) const noexcept {
        const int tx = int(t % std::size_t(tiles_x)), ty = int(t / std::size_t(tiles_x));
        return {tx * tile_size, ty * tile_size, std::min(res, (tx + 1) * tile_size), std::min(res, (ty + 1) * tile_size)};
    }

    /// The line walk's steps in tile t of segment s, ends within the guard band: how many of the texel
    /// centres it crosses along its major axis lie in the tile (avx512::major_steps::count, the same
    /// integers), at most tile_size.
    std::uint16_t walk_steps(const segment_geometry& s, std::size_t t) const noexcept {
        const texel_rect r = tile_rect(t);
        const std::int64_t dx = std::int64_t(s.bx) - s.ax, dy = std::int64_t(s.by) - s.ay;
        const bool x_major = (dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy);
        const std::int64_t a = x_major ? s.ax : s.ay, b = x_major ? s.bx : s.by;
        const std::int64_t origin = std::int64_t(x_major ? r.x0 : r.y0) * subpixel_scale, extent = x_major ? r.x1 - r.x0 : r.y1 - r.y0;
        // Centres c S + H crossed, in the tile's texels: first = ceil((lo - H) / S), last = ceil((hi - H) / S) - 1.
        const std::int64_t round_up = subpixel_scale - 1 - subpixel_scale / 2;
        const std::int64_t first = (std::min(a, b) - origin + round_up) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t last = ((std::max(a, b) - origin + round_up) >> HAIRSHADOW_SUBPIXEL_BITS) - 1;
        return std::uint16_t(std::max<std::int64_t>(std::min(last, extent - 1) - std::max<std::int64_t>(first, 0) + 1, 0));
    }

    /// texel / tile_size for a texel of the map, by a multiplication: q = (texel m) >> 32 with
    /// m = floor(2^32 / tile) + 1 is exact for texel < 2^16 and tile <= 2^10 (the error, texel (m tile -
    /// 2^32) / (tile 2^32) < 2^-16, stays below the gap 1 / tile to the next integer). It spares the
    /// binning a division per end per segment.
    HAIRSHADOW_ALWAYS_INLINE int tile_of(std::int64_t texel) const noexcept { return int((std::uint64_t(texel) * magic) >> 32); }

    /// Does the segment's bounding box, widened by `reach`, meet the map? The whole-map extent counts
    /// the segments that do, whatever the tiles.
    HAIRSHADOW_ALWAYS_INLINE bool meets_map(const segment_geometry& s, std::int64_t reach) const noexcept {
        const std::int64_t hi_x = (std::max<std::int64_t>(s.ax, s.bx) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t hi_y = (std::max<std::int64_t>(s.ay, s.by) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t lo_x = (std::min<std::int64_t>(s.ax, s.bx) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t lo_y = (std::min<std::int64_t>(s.ay, s.by) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        return !(hi_x < 0 || hi_y < 0 || lo_x >= res || lo_y >= res);
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
        const int tx0 = tile_of(std::max<std::int64_t>(lo_x, 0)), tx1 = tile_of(std::min<std::int64_t>(hi_x, res - 1));
        const int ty0 = tile_of(std::max<std::int64_t>(lo_y, 0)), ty1 = tile_of(std::min<std::int64_t>(hi_y, res - 1));
        if (ty0 == ty1 || tx0 == tx1) { // most hair segments: one row or column of tiles, as the box says
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) visit(std::size_t(ty) * std::size_t(tiles_x) + std::size_t(tx), tx, ty);
            return;
        }
        // A segment across several rows and columns: per row of tiles, only the columns that the
        // segment's piece in that row's band (widened by reach) spans, floored and ceiled outwards.
        const std::int64_t side = std::int64_t(tile_size) * subpixel_scale;
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
            for (int tx = c0; tx <= c1; ++tx) visit(std::size_t(ty) * std::size_t(tiles_x) + std::size_t(tx), tx, ty);
        }
    }
};

} // namespace hairshadow::detail
