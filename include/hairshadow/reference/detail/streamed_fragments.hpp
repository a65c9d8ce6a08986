#pragma once
/// @file
/// The exact map's fragments, tile by tile: a model's segments binned into the map's tiles (as every
/// other method's build does), each tile's fragments made, grouped by texel in segment order, and
/// handed to the map's builder, then the tile's memory reused for the next. No buffer of the whole
/// map's fragments is ever made: working memory is a tile's fragments per thread.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/raster_options.hpp>
#include <hairshadow/raster/detail/segment_bins.hpp>
#include <hairshadow/reference/detail/tile_lists.hpp>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <vector>

namespace hairshadow {

/// Called as tiles of a streamed build finish: (tiles done, tiles in all), from one thread at a time.
using build_progress = std::function<void(std::size_t done, std::size_t total)>;

namespace detail {

/// One tile's fragments grouped by texel: texel i of the tile (row-major) has fragments
/// [offsets[i], offsets[i + 1]), in the order of the segments that made them.
struct grouped_tile {
    std::span<const std::uint32_t> offsets;
    std::span<const fragment> fragments;
    std::span<const fragment> texel(std::size_t i) const noexcept { return fragments.subspan(offsets[i], offsets[i + 1] - offsets[i]); }
};

/// A slot's working memory for grouping one tile's fragments; kept from tile to tile.
struct tile_fragment_scratch {
    std::vector<std::uint32_t> texel_of; ///< each made fragment's texel within the tile
    std::vector<fragment> made, grouped;
    std::vector<std::uint32_t> offsets;

    std::size_t memory_bytes() const noexcept {
        return (texel_of.capacity() + offsets.capacity()) * sizeof(std::uint32_t) + (made.capacity() + grouped.capacity()) * sizeof(fragment);
    }
};

/// Makes tile t's fragments exactly as the rasterizer does (the same shading, the same order within
/// a texel: segment order) and groups them by texel, a counting sort that keeps that order.
inline grouped_tile group_tile_fragments(const segment_bins& bins, std::size_t t, tile_fragment_scratch& g) {
    const texel_rect rect = bins.tile_rect(t);
    const std::size_t w = std::size_t(rect.x1 - rect.x0), texels = w * std::size_t(rect.y1 - rect.y0);
    g.texel_of.clear(), g.made.clear();
    g.offsets.assign(texels + 1, 0);
    bins.for_each_fragment(t, [&](const segment_shader& s, int x, int y, float param, float weight) HAIRSHADOW_ALWAYS_INLINE {
        if (param < 0.0f) param = s.parameter(x, y);
        const std::uint32_t i = std::uint32_t(std::size_t(y - rect.y0) * w + std::size_t(x - rect.x0));
        ++g.offsets[i + 1];
        g.texel_of.push_back(i);
        g.made.push_back(s.shade(param, weight));
    });
    if (g.made.size() > std::numeric_limits<std::uint32_t>::max())
        throw argument_error("one tile of the map makes more than 2^32 fragments; use a smaller tile size");
    for (std::size_t i = 0; i < texels; ++i) g.offsets[i + 1] += g.offsets[i];
    g.grouped.resize(g.made.size());
    for (std::size_t f = 0; f < g.made.size(); ++f) g.grouped[g.offsets[g.texel_of[f]]++] = g.made[f];
    for (std::size_t i = texels; i > 0; --i) g.offsets[i] = g.offsets[i - 1]; // the cursors ended where the next texel begins
    g.offsets[0] = 0;
    return {g.offsets, g.grouped};
}

} // namespace detail

/// The working memory of the streamed exact maps' builds: the binned segments and each thread's tile
/// of fragments. A map built once frees it with the build; a caller that rebuilds (a renderer, the
/// registry's exact map) passes one to keep it, and touches no new pages on the next build.
struct streamed_workspace {
    detail::segment_bins bins;
    std::vector<detail::tile_fragment_scratch> tiles;
    std::size_t memory_bytes() const noexcept {
        std::size_t n = bins.memory_bytes();
        for (const auto& t : tiles) n += t.memory_bytes();
        return n;
    }
};

namespace detail {

/// Bins `model`'s segments into `light`'s map in tiles of options.tile_size and calls
/// build(slot, t, grouped_tile) for every tile, the largest first, on options.exec's threads; `slot`
/// tells apart the threads running at once (for the builder's own scratch: streamed_slots of it).
/// Tiles are map_tiling(light.resolution(), options.tile_size)'s. Reports each finished tile to
/// `progress`. Throws argument_error for bad options.
template <class Build>
void stream_tiles(streamed_workspace& w, const hair_model& model, const light_space& light, const raster_options& options, const build_progress& progress,
                  Build&& build) {
    segment_bins& bins = w.bins;
    bins.prepare(model, light, options, false);
    const std::size_t tiles = bins.tile_count();
    auto& scratch = w.tiles;
    scratch.resize(std::max<std::size_t>(scratch.size(), parallel_slots(tiles, options.exec)));
    std::size_t done = 0; // counted under the lock, so that reports come in order
    std::mutex report;
    parallel_for_slots(tiles, options.exec, [&](unsigned slot, std::size_t i) {
        const std::size_t t = bins.tiles_by_load()[i];
        build(slot, t, group_tile_fragments(bins, t, scratch[slot]));
        if (progress) {
            std::lock_guard lock(report);
            progress(++done, tiles);
        }
    });
}

/// The tile size of `options`, once the options are checked (argument_error where they are bad): the
/// map's tiling is made from it before stream_tiles bins anything.
inline int checked_tile_size(const raster_options& options) {
    options.check();
    return options.tile_size;
}

/// Slots of builder scratch that stream_tiles may use.
inline unsigned streamed_slots(const light_space& light, const raster_options& options) noexcept {
    return parallel_slots(map_tiling(light.resolution(), options.tile_size).tile_count(), options.exec);
}

} // namespace detail
} // namespace hairshadow
