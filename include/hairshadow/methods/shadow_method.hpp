#pragma once
/// @file
/// A shadow method composed of a placement, an accumulation and a reconstruction policy, with its
/// CPU kernels: the placement's pre-passes, then one accumulation pass, texel by texel in parallel;
/// built tile by tile straight from a model, or from a buffer of fragments.

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/map_queries.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/detail/huge_pages.hpp>
#include <hairshadow/core/detail/tail_bytes.hpp>
#include <hairshadow/methods/concepts.hpp>
#include <hairshadow/methods/detail/build_plan.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/raster_options.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace hairshadow {

/// A shadow method: `Placement` decides the layers, `Accumulation` how fragments sum into them and
/// `Reconstruction` what is stored and read back. The published methods are aliases of this template
/// (methods/published.hpp); any other valid composition is a hybrid.
/// @tparam Placement a placement_policy (uniform_slices, gamma_slices, per_pixel_depth, clustered, depth_range)
/// @tparam Accumulation an accumulation_policy (float_accumulation, emulated_8bit)
/// @tparam Reconstruction a reconstruction_policy (interpolation, occupancy_bitcount, fibre_density)
template <class Placement, class Accumulation, class Reconstruction>
class shadow_method : public map_queries<shadow_method<Placement, Accumulation, Reconstruction>> {
    static_assert(placement_policy<Placement>,
                  "Placement must provide layer_count, cumulative, glsl_name, texel_state, prepare(depth_extent), prepare_texel(fragments, state) "
                  "for spans of fragment and optical_fragment, assign(state, depth) -> int and locate(state, depth) -> layer_position "
                  "- see docs/policies.md");
    static_assert(accumulation_policy<Accumulation>,
                  "Accumulation must provide value_type, sum_type, add(sum, b), combine(sum, sum), store(sum), decode(value) -> float "
                  "and glsl_name - see docs/policies.md");
    static_assert(reconstruction_policy<Reconstruction, Placement, Accumulation>,
                  "Reconstruction must provide accepts<Placement>, storage<Placement, Accumulation>, build(...), optical_depth(...) "
                  "and glsl_name - see docs/policies.md");
    static_assert(Reconstruction::template accepts<Placement>,
                  "this Reconstruction cannot read this Placement's layers: occupancy_bitcount<B> needs contiguous slices whose "
                  "count is a multiple of 32 and of B (depth_range, per_pixel_depth, uniform_slices), not clustered bins; "
                  "fibre_density needs the first fragment (per_pixel_depth, depth_range), its measured form also the last (depth_range)");

public:
    using placement_type = Placement;
    using accumulation_type = Accumulation;
    using reconstruction_type = Reconstruction;
    static constexpr int layer_count = Placement::layer_count;

    /// What one texel of the maps holds.
    struct texel_maps {
        using storage_type = typename Reconstruction::template storage<Placement, Accumulation>;
        [[no_unique_address]] typename Placement::texel_state placement{};
        storage_type data{};
        /// The bytes that would be padding after the two parts (an 8-bit layer beside a float depth),
        /// named so that every texel written is written whole: maps_hash reads the texel's bytes.
        [[no_unique_address]] detail::tail_bytes<detail::tail_padding<typename Placement::texel_state, storage_type>(), texel_maps> tail{};
        /// Equal maps: every value equal (floats compare as floats).
        friend bool operator==(const texel_maps&, const texel_maps&) = default;
    };
    static_assert(padding_free<texel_maps>,
                  "a texel (the Placement's texel_state beside the Reconstruction's storage) must have no padding bytes, but at its end, and be "
                  "constant-initialisable: order a storage's fields by size, widen a field, or end the storage with "
                  "detail::tail_bytes<detail::tail_padding<Fields...>(), storage> - see docs/policies.md");

    /// A method with its policies' parameters (DOM's layer extent, a fibre density).
    explicit shadow_method(Placement placement = Placement(), Reconstruction reconstruction = Reconstruction())
        : placement_(std::move(placement)), reconstruction_(std::move(reconstruction)) {}

    /// Builds the maps of `model` for `light`, tile by tile (methods/detail/tiled_build.hpp): the fastest
    /// build, and the one to call every frame, since this object keeps its working memory. The
    /// whole-map values (OSM's near and far, DOM's default extent) come from the segments' ends
    /// (segment_bins::extent). Identical for any thread count and tile size, and equal to
    /// build(rasterize(model, light, options), light, map_extent()).
    void build(const hair_model& model, const light_space& light, const raster_options& options = {}) {
        auto& w = workspace_.get();
        // Bins first: the placement needs the extent before any tile. A first build (no tile stores
        // yet) bounds the tiles' fragments, to size the stores once; a rebuild reuses them.
        w.bins.prepare(model, light, options, w.tiles.empty());
        built_or_reset([&] {
            set_light(light);
            extent_ = w.bins.extent();
            placement_.prepare(extent_);
            const std::size_t res = std::size_t(light.resolution());
            resize_maps(res * res, options.exec);
            const auto texel_out = [&](int x, int y) -> texel_maps& { return texels_[std::size_t(y) * res + std::size_t(x)]; };
            fragments_ = detail::build_tiles<Placement, Accumulation, Reconstruction>(
                w, placement_, extent_, options, [&]() -> auto& { return streamed_.get(); }, texel_out,
                [&](auto fragments, texel_maps& out, instruction_set instructions) HAIRSHADOW_ALWAYS_INLINE { build_texel(fragments, out, instructions); },
                // generic: instantiated only by a composition that builds from depths
                [&](auto depths, float b, texel_maps& out) HAIRSHADOW_ALWAYS_INLINE { this->build_texel_from_depths(depths, b, out); });
        });
    }

    /// Builds the maps from the fragments of `light`'s map: the placement's global and per-texel
    /// pre-passes, then the accumulation pass. Identical for any thread count.
    void build(const fragment_buffer& fragments, const light_space& light, const execution& exec = {}) {
        build(fragments, light, extent_of(fragments), exec);
    }

    /// The same with the whole-map extent given (by default the fragments' own): the tiled build's
    /// map_extent() gives the tiled build's maps.
    void build(const fragment_buffer& fragments, const light_space& light, const depth_extent& extent, const execution& exec = {}) {
        if (fragments.resolution() != light.resolution()) throw argument_error("fragment buffer and light differ in resolution");
        built_or_reset([&] {
            set_light(light);
            extent_ = extent;
            placement_.prepare(extent);
            fragments_ = fragments.size();
            resize_maps(fragments.texel_count(), exec);
            parallel_for(texels_.size(), exec, [&](std::size_t t) { build_texel(fragments.texel(t), texels_[t], instruction_set::scalar); }, 512);
        });
    }

    /// Takes maps built elsewhere (on GL: interpolated_maps_gl::to_cpu()) for CPU queries: one texel per
    /// texel of `light`'s map, row by row, and the placement they were built with.
    void adopt(const light_space& light, Placement placement, std::vector<texel_maps> texels) {
        const std::size_t res = std::size_t(light.resolution());
        if (texels.size() != res * res) throw argument_error("adopted maps need one texel per texel of the light's map");
        set_light(light);
        placement_ = std::move(placement);
        texels_.assign(texels.begin(), texels.end());
    }

    /// Optical depth at linear `depth` in texel (x, y).
    float optical_depth(int x, int y, float depth) const noexcept {
        const auto& t = texel(x, y);
        return reconstruction_.template optical_depth<Placement, Accumulation>(placement_, t.placement, t.data, depth);
    }
    using map_queries<shadow_method>::transmittance;

    /// Number of maps the method stores (layers, bins or slabs), for inspection.
    static constexpr int stored_maps = Reconstruction::template stored_maps<Placement>;
    /// Optical depth stored in map k of texel (x, y): through the end of layer, bin or slab k.
    float stored_optical_depth(int x, int y, int k) const noexcept {
        return Reconstruction::template stored_optical_depth<Placement, Accumulation>(texel(x, y).data, k);
    }

    const texel_maps& texel(int x, int y) const noexcept { return texels_[std::size_t(y) * std::size_t(light_.resolution()) + std::size_t(x)]; }
    const Placement& placement() const noexcept { return placement_; }
    const Reconstruction& reconstruction() const noexcept { return reconstruction_; }
    /// The whole-map depth extent of the last build: the fragments' own, or the segments' in a build
    /// from the model.
    const depth_extent& map_extent() const noexcept { return extent_; }
    /// Fragments the last build summed.
    std::size_t fragment_count() const noexcept { return fragments_; }
    /// Bytes of working memory the tiled build keeps between builds (not part of the maps).
    std::size_t workspace_bytes() const noexcept {
        std::size_t bytes = workspace_.peek() ? workspace_.peek()->memory_bytes() : 0;
        if (const auto* per_thread = streamed_.peek())
            for (const auto& s : *per_thread) bytes += s.memory_bytes();
        return bytes;
    }
    const light_space& light() const noexcept { return light_; }
    /// Bytes the maps hold: every texel's placement state and stored layers, plus the global state.
    std::size_t memory_bytes() const noexcept { return texels_.size() * sizeof(texel_maps) + placement_global_bytes<Placement>(); }
    /// Bytes per texel.
    static constexpr std::size_t texel_bytes() noexcept { return sizeof(texel_maps); }

private:
    /// One texel's maps from its fragments (fragment or optical_fragment), in segment order (or any,
    /// for an order-free composition: detail::order_free_maps), with the
    /// vector steps `instructions` (resolved) allows (placement/detail/assign_each.hpp): the same maps.
    template <class Fragment>
    HAIRSHADOW_ALWAYS_INLINE void build_texel(std::span<const Fragment> in, texel_maps& out, instruction_set instructions) const {
        out = texel_maps{};
        if (in.empty()) return;
        detail::prepare_texel(placement_, in, out.placement, instructions);
        if constexpr (requires { reconstruction_.template build<Placement, Accumulation>(placement_, out.placement, in, out.data, instructions); })
            reconstruction_.template build<Placement, Accumulation>(placement_, out.placement, in, out.data, instructions);
        else
            reconstruction_.template build<Placement, Accumulation>(placement_, out.placement, in, out.data);
    }

    /// build_texel for a texel whose fragments all have optical depth b, given by their depths alone:
    /// the same maps (detail::builds_from_depths_avx512; instantiated only where the plan calls it).
    void build_texel_from_depths(std::span<const float> depths, float b, texel_maps& out) const {
        out = texel_maps{};
        if (depths.empty()) return;
        placement_.prepare_texel_depths_avx512(depths, b, out.placement);
        Reconstruction::template build_from_depths<Placement, Accumulation>(placement_, out.placement, depths, b, out.data);
    }

    /// The light of the maps, given to a reconstruction that needs it (a fibre density's world units).
    void set_light(const light_space& light) {
        light_ = light;
        if constexpr (requires { reconstruction_.prepare(light); }) reconstruction_.prepare(light);
    }

    /// Resizes the maps to `texels` texels, the new ones zeroed (every byte: the maps' bytes are the
    /// same for any thread count) in parallel, so that the build's threads, not one, first touch
    /// their pages and share the cost of a cold build's fresh memory, high on a virtual machine
    /// (BENCHMARKS.md, "Density clustering walks in any order; the maps cleared by the build's
    /// threads"). The bytes are split at 2 MiB boundaries, so that each huge page is first touched by
    /// one thread: the kernel clears a huge page whole, and a second thread touching it would wait.
    void resize_maps(std::size_t texels, const execution& exec) {
        const std::size_t old = texels_.size();
        texels_.resize(texels); // leaves the new texels as allocated (overwritten_huge_page_allocator)
        if (texels <= old) return;
        constexpr std::size_t page = detail::huge_page_allocator<texel_maps>::huge_page;
        auto* const bytes = reinterpret_cast<unsigned char*>(texels_.data() + old);
        const std::size_t size = (texels - old) * sizeof(texel_maps);
        const std::size_t before = std::size_t(reinterpret_cast<std::uintptr_t>(bytes) % page); // into the first page
        parallel_for((before + size + page - 1) / page, exec, [&](std::size_t i) {
            const std::size_t lo = i == 0 ? 0 : i * page - before, hi = std::min(size, (i + 1) * page - before);
            std::memset(bytes + lo, 0, hi - lo);
        });
    }

    /// Runs a build; if it throws (out of memory, say), the maps go back to the unbuilt state, never to
    /// a light whose resolution the texels do not match.
    template <class Build>
    void built_or_reset(Build&& build) {
        try {
            build();
        } catch (...) {
            set_light(light_space());
            texels_.assign(1, texel_maps{});
            extent_ = {};
            fragments_ = 0;
            throw;
        }
    }

    Placement placement_;
    [[no_unique_address]] Reconstruction reconstruction_;
    light_space light_;                                  // 1x1 until built, so early queries see no shadow
    /// Row by row. Grown only by resize_maps, which zeroes the new texels in parallel.
    std::vector<texel_maps, detail::overwritten_huge_page_allocator<texel_maps>> texels_ = decltype(texels_)(1, texel_maps{});
    depth_extent extent_{};
    std::size_t fragments_ = 0;
    detail::scratch<detail::tiled_workspace> workspace_;
    using streamed_tile = detail::streamed_tile_for<Placement, Accumulation, Reconstruction>;
    detail::scratch<std::vector<streamed_tile>> streamed_; ///< per thread, where the composition streams
};

} // namespace hairshadow
