#pragma once
/// @file
/// The exact reference (Lokovic & Veach 2000): every texel keeps its fragments sorted by depth, so the
/// optical depth Omega(z) = sum over fragments in front of z of -ln(1 - alpha_i) and the transmittance
/// T = exp(-Omega) are exact at any depth. This is what infinitely many opacity slices, or depth
/// peeling, would give; every method is measured against it.
///
/// Built from a model, the map is streamed (section 3 of the paper builds it tile by tile too): each
/// tile's fragments are made, sorted into its texels' functions and stored, and the tile's memory
/// reused, so no buffer of the whole map's fragments exists. Built from a fragment buffer, it is the
/// same map, bit for bit.

#include <hairshadow/core/light.hpp>
#include <hairshadow/core/map_queries.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/reference/detail/streamed_fragments.hpp>
#include <hairshadow/reference/detail/tile_lists.hpp>

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

namespace hairshadow {

namespace detail {
/// Scratch for sorting one texel's fragments, kept from texel to texel.
using depth_order = std::vector<std::pair<float, std::uint32_t>>;

/// Sorts one texel's fragments by depth (equal depths keep their order, for any thread count) and
/// writes their depths and the optical depth behind each (inclusive prefix sums, in double).
inline void sort_texel(std::span<const fragment> in, depth_order& order, float* depths, float* optical_depths) {
    order.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) order[i] = {in[i].depth, std::uint32_t(i)};
    std::sort(order.begin(), order.end());
    double omega = 0.0;
    for (std::size_t i = 0; i < order.size(); ++i) {
        omega -= std::log1p(-double(in[order[i].second].alpha));
        depths[i] = order[i].first;
        optical_depths[i] = float(omega);
    }
}

/// Tile t's texels' fragments, from a whole-map fragment buffer.
struct buffer_tile {
    const fragment_buffer& fragments;
    const map_tiling& tiling;
    std::size_t t;
    std::span<const fragment> texel(std::size_t i) const noexcept {
        const int w = tiling.width(t);
        return fragments.texel(tiling.x0(t) + int(i % std::size_t(w)), tiling.y0(t) + int(i / std::size_t(w)));
    }
};
} // namespace detail

/// Per-texel sorted fragment lists with cumulative optical depth.
class deep_shadow_map : public map_queries<deep_shadow_map> {
public:
    /// Sorts every texel's fragments by depth (ties keep segment order) and accumulates optical depth.
    deep_shadow_map(const fragment_buffer& fragments, const light_space& light, const execution& exec = {})
        : light_(light), lists_(detail::map_tiling(light.resolution(), buffer_tile_size)) {
        if (fragments.resolution() != light.resolution()) throw argument_error("fragment buffer and light differ in resolution");
        std::vector<scratch> slots(parallel_slots(lists_.tiling().tile_count(), exec));
        parallel_for_slots(lists_.tiling().tile_count(), exec, [&](unsigned slot, std::size_t t) {
            build_tile(t, detail::buffer_tile{fragments, lists_.tiling(), t}, slots[slot]);
        });
    }

    /// Streams `model`'s fragments tile by tile into the map (options.tile_size texels a side), never
    /// holding more than one tile's fragments a thread; the same map as from rasterize(model, light,
    /// options). `progress` hears each finished tile; `workspace`, where given, keeps the working
    /// memory for the next build. Throws argument_error for bad options.
    deep_shadow_map(const hair_model& model, const light_space& light, const raster_options& options = {}, const build_progress& progress = {},
                    streamed_workspace* workspace = nullptr)
        : light_(light), lists_(detail::map_tiling(light.resolution(), detail::checked_tile_size(options))) {
        streamed_workspace own;
        std::vector<scratch> slots(detail::streamed_slots(light, options));
        detail::stream_tiles(workspace ? *workspace : own, model, light, options, progress, [&](unsigned slot, std::size_t t, const detail::grouped_tile& tile) {
            build_tile(t, tile, slots[slot]);
        });
    }

    const light_space& light() const noexcept { return light_; }
    int resolution() const noexcept { return light_.resolution(); }

    /// Sorted depths of texel (x, y)'s fragments.
    std::span<const float> depths(int x, int y) const noexcept { return lists_.list(x, y, 0); }
    /// Optical depth behind each of texel (x, y)'s fragments (inclusive prefix sums).
    std::span<const float> optical_depths(int x, int y) const noexcept { return lists_.list(x, y, 1); }

    /// Exact optical depth at `depth` in texel (x, y): the fragments strictly in front count.
    float optical_depth(int x, int y, float depth) const noexcept {
        const auto d = depths(x, y);
        const std::size_t in_front = std::size_t(std::lower_bound(d.begin(), d.end(), depth) - d.begin());
        return in_front == 0 ? 0.0f : optical_depths(x, y)[in_front - 1];
    }
    using map_queries<deep_shadow_map>::transmittance;

    std::size_t fragment_count() const noexcept { return lists_.size(); }
    /// Bytes held by the map: each texel's place in its tile's block, depths and optical depths.
    std::size_t memory_bytes() const noexcept { return lists_.memory_bytes(); }

private:
    static constexpr int buffer_tile_size = 64;
    struct scratch {
        std::vector<std::uint64_t> lengths;
        detail::depth_order order;
    };

    template <class Tile>
    void build_tile(std::size_t t, const Tile& tile, scratch& s) {
        const std::size_t texels = std::size_t(lists_.tiling().width(t)) * std::size_t(lists_.tiling().height(t));
        s.lengths.resize(texels);
        for (std::size_t i = 0; i < texels; ++i) s.lengths[i] = tile.texel(i).size();
        lists_.write_tile(t, s.lengths, [&](std::vector<float>& block, std::size_t n) {
            std::size_t at = 0;
            for (std::size_t i = 0; i < texels; ++i) {
                detail::sort_texel(tile.texel(i), s.order, block.data() + at, block.data() + n + at);
                at += s.lengths[i];
            }
        });
    }

    light_space light_;
    detail::tile_lists<float, 2> lists_; ///< depths (array 0) and optical depths (array 1)
};

} // namespace hairshadow
