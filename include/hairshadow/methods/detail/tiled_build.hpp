#pragma once
/// @file
/// The tiled build: every method's maps built tile by tile straight from the model, with no buffer of
/// the whole map's fragments. Segments are projected and binned once (segment_bins); then each tile,
/// in parallel, gathers its fragments into a per-thread store that stays in cache, and every texel of
/// the tile is built from its own fragments, in segment order, exactly as from a fragment_buffer
/// (or, where the method's maps cannot tell the order, in the walk's own: fragment_order::any).

#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/detail/segment_bins.hpp>
#include <hairshadow/raster/detail/tile_fragments.hpp>

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

namespace hairshadow::detail {

/// What the tiled build keeps from one build to the next: the binned segments and one tile store per
/// thread. A renderer that rebuilds its maps every frame allocates nothing after the first.
struct tiled_workspace {
    segment_bins bins;
    std::vector<tile_fragments> tiles;
    std::vector<std::size_t> fragments; ///< per thread, in the last build

    std::size_t memory_bytes() const noexcept {
        std::size_t bytes = bins.memory_bytes();
        for (const auto& t : tiles) bytes += t.memory_bytes();
        return bytes;
    }
};

/// Scratch memory owned by an object but not part of its value: copies and moves of the owner start
/// without it, and it is made at first use.
template <class T>
class scratch {
public:
    scratch() = default;
    scratch(const scratch&) noexcept {}
    scratch& operator=(const scratch&) noexcept { return *this; }
    T& get() {
        if (!value_) value_ = std::make_unique<T>();
        return *value_;
    }
    const T* peek() const noexcept { return value_.get(); }

private:
    std::unique_ptr<T> value_;
};

/// The number of threads (slots) for_each_tile runs the tiles of w.bins on.
inline unsigned tile_slots(const tiled_workspace& w) noexcept { return parallel_slots(w.bins.tiles_by_load().size(), w.bins.options().exec); }

/// What for_each_tile does with a tile's fragments after the walk.
enum class tile_grouping {
    grouped,    ///< groups them by texel (tile_fragments::texel)
    /// groups their depths alone by texel (tile_fragments::texel_depths), for a map whose fragments
    /// share one optical depth (tile_fragments::one_optical_depth)
    grouped_depths,
    walk_order, ///< leaves them in walk order
    on_demand,  ///< leaves them in walk order; on_tile may group them (tile_fragments::group)
};

/// Calls on_tile(slot, tile) for every tile of the map that w.bins was prepared for, in parallel
/// (the tiles with the most segments first), with the tile's fragments gathered in `slot`'s store,
/// in the order `fragments_in` allows, and grouped as `grouping` says. Returns the number of fragments.
template <class OnTile>
std::size_t for_each_tile(tiled_workspace& w, tile_grouping grouping, OnTile&& on_tile, fragment_order fragments_in = fragment_order::segment) {
    const auto& order = w.bins.tiles_by_load();
    const execution& exec = w.bins.options().exec;
    const instruction_set instructions = resolve(w.bins.options().instructions);
    const unsigned slots = tile_slots(w);
    const auto side = std::size_t(w.bins.options().tile_size);
    w.tiles.resize(slots);
    w.fragments.assign(slots, 0);
    // Room for the largest tile before any walk (segment_bins::tile_fragment_bound, thin lines): no
    // store grows in the middle of a tile, holding its old and new memory at once, or overshoots.
    // The walk adds a segment only where its steps and 1 more fit (at most the tile's side and 1),
    // or sixteen at once (in any order) where theirs and 16 more fit: each segment's steps and start
    // exceed its bound by at most 1.
    if (const std::size_t most = w.bins.largest_tile_fragment_bound(); most > 0)
        for (auto& tile : w.tiles)
            tile.reserve_fresh(most + side + 16, grouping == tile_grouping::grouped ? most : 0, grouping == tile_grouping::grouped_depths ? most : 0);
    if (fragments_in == fragment_order::any && instructions == instruction_set::avx512 && !order.empty()) // the vector walk sorts
        for (auto& tile : w.tiles) tile.reserve_segments(w.bins.tile_load(order[0]), int(side)); // the most segments first
    parallel_for_slots(order.size(), exec, [&](unsigned slot, std::size_t i) {
        tile_fragments& tile = w.tiles[slot];
        tile.gather(w.bins, order[i], instructions, fragments_in);
        if (grouping == tile_grouping::grouped) tile.group();
        else if (grouping == tile_grouping::grouped_depths) tile.group_depths();
        w.fragments[slot] += tile.size();
        on_tile(slot, tile);
    });
    // Every thread's store as large as the largest: the tiles go to other threads in the next build,
    // which then allocates nothing.
    std::size_t largest = 0, largest_grouped = 0, largest_depths = 0;
    for (const auto& tile : w.tiles) {
        largest = std::max(largest, tile.capacity());
        largest_grouped = std::max(largest_grouped, tile.grouped_capacity());
        largest_depths = std::max(largest_depths, tile.grouped_depths_capacity());
    }
    for (auto& tile : w.tiles) tile.reserve(largest, largest_grouped, largest_depths, side * side);
    std::size_t total = 0;
    for (const std::size_t n : w.fragments) total += n;
    return total;
}

/// Calls build_texel(x, y, fragments) for every texel of the map that w.bins was prepared for (so the
/// whole-map pre-pass, w.bins.extent(), is known before), tile by tile in parallel, with the texel's
/// optical_fragments in segment order (empty where no fragment falls). Each texel is visited once,
/// from one thread, so build_texel may write the texel's own output without locks.
/// Returns the number of fragments.
template <class BuildTexel>
std::size_t build_tiles(tiled_workspace& w, BuildTexel&& build_texel) {
    return for_each_tile(w, tile_grouping::grouped, [&](unsigned, const tile_fragments& tile) {
        const texel_rect r = tile.rect();
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) build_texel(x, y, tile.texel(x, y));
    });
}

} // namespace hairshadow::detail

namespace hairshadow {

/// The number of fragments `model` makes in `light`'s map: what a fragment_buffer would hold, counted
/// tile by tile without one.
inline std::size_t count_fragments(const hair_model& model, const light_space& light, const raster_options& options = {}) {
    detail::tiled_workspace w;
    w.bins.prepare(model, light, options, true);
    return detail::for_each_tile(w, detail::tile_grouping::walk_order, [](unsigned, const detail::tile_fragments&) {});
}

} // namespace hairshadow
