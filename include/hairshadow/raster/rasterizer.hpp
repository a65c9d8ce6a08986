#pragma once
/// @file
/// Rasterises a hair model's segments into one buffer of light-space fragments (texel, depth, alpha),
/// in parallel tiles, with per-texel output identical for any thread count. The exact reference and
/// users who want the fragments themselves need it; the methods build tile by tile without it
/// (methods/detail/tiled_build.hpp).

#include <hairshadow/config.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/raster_options.hpp>
#include <hairshadow/raster/detail/segment_bins.hpp>

#include <cstdint>
#include <vector>

namespace hairshadow {

/// Rasterises hair models into light-space fragments, keeping its working memory between calls so
/// that a renderer rebuilding its maps every frame touches no new pages. Fragments follow the GL line
/// rule (or the wide-line filter); a fragment's alpha is the strand's opacity times the share of the
/// texel its thickness covers (thickness / texel footprint, at most 1), or the fixed alpha; either is
/// clamped to HAIRSHADOW_ALPHA_MAX.
class rasterizer {
public:
    /// Throws argument_error for a bad alpha, wide-line width or tile size.
    explicit rasterizer(const raster_options& options = {}) : opt_(options) { opt_.check(); }

    const raster_options& options() const noexcept { return opt_; }

    /// Rasterises every segment of `model` into `light`'s map. The result stays valid until the next
    /// call (move it out to keep it).
    fragment_buffer& operator()(const hair_model& model, const light_space& light) {
        bins_.prepare(model, light, opt_);
        fill();
        return out_;
    }

    /// The whole-map depth extent of the last call's segments (segment_bins::extent): the tiled build
    /// places OSM's slices and DOM's layers with it.
    depth_extent segment_extent() const noexcept { return bins_.extent(); }

private:
    // Rasterise each tile into its own buffer (kept between calls) while counting every texel's
    // fragments; then, once the offsets are known, scatter each tile's fragments to their texels in
    // the order they were made, which is segment order.
    void fill() {
        const int res = bins_.resolution();
        const std::size_t tile_count = bins_.tile_count();
        const std::size_t texels = std::size_t(res) * std::size_t(res);
        auto& offsets = out_.offsets_;
        offsets.assign(texels + 1, 0);
        tile_fragments_.resize(tile_count);
        parallel_for(tile_count, opt_.exec, [&](std::size_t i) {
            const std::size_t t = bins_.tiles_by_load()[i];
            // Work on a local vector: neighbouring tiles' vector headers share cache lines.
            auto made = std::move(tile_fragments_[t]);
            made.clear();
            bins_.for_each_fragment(t, [&](const detail::segment_shader& s, int x, int y, float param, float weight) HAIRSHADOW_ALWAYS_INLINE {
                if (param < 0.0f) param = s.parameter(x, y);
                const std::size_t texel = std::size_t(y) * std::size_t(res) + std::size_t(x);
                ++offsets[texel + 1];
                made.push_back({std::uint32_t(texel), s.shade(param, weight)});
            });
            tile_fragments_[t] = std::move(made);
        });
        for (std::size_t i = 0; i < texels; ++i) offsets[i + 1] += offsets[i];
        out_.resolution_ = res;
        out_.fragments_.resize(offsets.back());
        parallel_for(tile_count, opt_.exec, [&](std::size_t t) {
            const auto& made = tile_fragments_[t];
            if (made.empty()) return;
            const texel_rect rect = bins_.tile_rect(t);
            const std::size_t w = std::size_t(rect.x1 - rect.x0);
            std::vector<std::uint64_t> cursor(w * std::size_t(rect.y1 - rect.y0));
            for (int y = rect.y0; y < rect.y1; ++y)
                for (int x = rect.x0; x < rect.x1; ++x)
                    cursor[std::size_t(y - rect.y0) * w + std::size_t(x - rect.x0)] = offsets[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            for (const auto& m : made) {
                const std::size_t x = m.texel % std::size_t(res), y = m.texel / std::size_t(res);
                out_.fragments_[cursor[(y - std::size_t(rect.y0)) * w + (x - std::size_t(rect.x0))]++] = m.value;
            }
        });
    }

    struct placed_fragment {
        std::uint32_t texel;
        fragment value;
    };

    fragment_buffer out_;
    raster_options opt_;
    detail::segment_bins bins_;
    std::vector<std::vector<placed_fragment>> tile_fragments_;
};

/// Rasterises every segment of `model` into `light`'s map (a one-shot rasterizer).
inline fragment_buffer rasterize(const hair_model& model, const light_space& light, const raster_options& options = {}) {
    rasterizer r(options);
    return std::move(r(model, light));
}

} // namespace hairshadow
