#pragma once
/// @file
/// The tiled build's plan: how a composition's tiles are built, chosen from its capabilities
/// (policies/capabilities.hpp), the model and the CPU, in one place. Every path gives the same maps,
/// bit for bit:
/// 1. streamed (streams_tiles): dense tiles reduce their fragments where the walk left them
///    (methods/detail/streamed_tile.hpp); sparse ones are grouped, which is cheaper there;
/// 2. depths alone (builds_from_depths_avx512, every fragment of one optical depth, AVX-512): the
///    tiles group their depths alone, half the bytes of the grouping's scatter and of the texels'
///    passes (BENCHMARKS.md, "Density clustering groups depths alone where a map has one optical depth");
/// 3. grouped: every tile's fragments gathered by texel, then the texel's pre-pass and build.
/// Each path walks a tile in any order where the maps cannot tell (order_free_maps, and no depth of
/// -0: walks_in_any_order), so that long segments walk side by side in lanes of nearly one length
/// (BENCHMARKS.md, "Tiles walked in any order where the maps cannot tell").

#include <hairshadow/methods/detail/streamed_tile.hpp>
#include <hairshadow/methods/detail/tiled_build.hpp>
#include <hairshadow/policies/capabilities.hpp>

#include <cstddef>
#include <vector>

namespace hairshadow::detail {

/// Builds every tile of `w` (binned already) by the composition's plan. `texel_out(x, y)` is the
/// texel's maps; `build_texel(fragments, out, instructions)` and `build_from_depths(depths, b, out)`
/// build one texel; `streamed()` gives the per-thread stores, asked for only by a composition that
/// streams. Gives the fragments walked.
template <class Placement, class Accumulation, class Reconstruction, class Streamed, class TexelOut, class BuildTexel, class BuildFromDepths>
std::size_t build_tiles(tiled_workspace& w, const Placement& placement, const depth_extent& extent, const raster_options& options,
                        Streamed&& streamed, TexelOut&& texel_out, BuildTexel&& build_texel, BuildFromDepths&& build_from_depths) {
    const instruction_set instructions = resolve(options.instructions);
    const auto build_grouped = [&](const tile_fragments& tile) {
        const texel_rect r = tile.rect();
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) build_texel(tile.texel(x, y), texel_out(x, y), instructions);
    };
    const auto order = walks_in_any_order<Placement, Reconstruction>(extent) ? fragment_order::any : fragment_order::segment;
    if constexpr (streams_tiles<Placement, Accumulation, Reconstruction>) {
        auto& per_thread = streamed();
        per_thread.resize(tile_slots(w));
        for (auto& s : per_thread) s.reserve(std::size_t(options.tile_size) * std::size_t(options.tile_size));
        return for_each_tile(
            w, tile_grouping::on_demand,
            [&](unsigned slot, tile_fragments& tile) {
                if (per_thread[slot].pays(tile)) return per_thread[slot].build(placement, tile, instructions, texel_out);
                tile.group();
                build_grouped(tile);
            },
            order);
    } else {
#if HAIRSHADOW_AVX512_WALK
        if constexpr (builds_from_depths_avx512<Placement, Accumulation, Reconstruction>) {
            if (instructions == instruction_set::avx512 && tile_fragments::one_optical_depth(w.bins)) {
                const float b = tile_fragments::shared_optical_depth(w.bins);
                return for_each_tile(
                    w, tile_grouping::grouped_depths,
                    [&](unsigned, const tile_fragments& tile) {
                        const texel_rect r = tile.rect();
                        for (int y = r.y0; y < r.y1; ++y)
                            for (int x = r.x0; x < r.x1; ++x) build_from_depths(tile.texel_depths(x, y), b, texel_out(x, y));
                    },
                    order);
            }
        }
#endif
        (void)build_from_depths;
        return for_each_tile(w, tile_grouping::grouped, [&](unsigned, const tile_fragments& tile) { build_grouped(tile); }, order);
    }
}

} // namespace hairshadow::detail
