#pragma once
/// @file
/// Lokovic & Veach's compression of a deep shadow map: each texel's transmittance function becomes a
/// piecewise-linear function with as few vertices as the greedy algorithm of their section 4.2 allows
/// while staying within `tolerance` of the exact function at every depth.

#include <hairshadow/reference/deep_shadow_map.hpp>

#include <atomic>
#include <limits>

namespace hairshadow {

/// One vertex of a compressed transmittance function.
struct transmittance_vertex {
    float depth;
    float transmittance;
};

namespace detail {
/// Greedy compression of a piecewise-linear function given by `in` (depths non-decreasing; equal depths
/// are vertical steps). Each output segment starts where the last ended and is extended while some
/// slope keeps it within `eps` of every input vertex it spans; its slope is the middle of the range.
inline void compress_function(std::span<const transmittance_vertex> in, float eps, std::vector<transmittance_vertex>& out) {
    if (in.empty()) return;
    transmittance_vertex origin = in[0];
    out.push_back(origin);
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    float reach = origin.depth; // depth of the last vertex the current segment covers
    auto close_segment = [&] {
        const double slope = 0.5 * (lo + hi);
        origin = {reach, float(origin.transmittance + slope * (double(reach) - origin.depth))};
        out.push_back(origin);
        lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    };
    for (std::size_t j = 1; j < in.size(); ++j) {
        const auto v = in[j];
        const double dz = double(v.depth) - origin.depth;
        if (dz <= 0.0) { // at the origin's depth: a vertical step if it moves more than eps
            if (std::abs(v.transmittance - origin.transmittance) > eps) {
                origin.transmittance = v.transmittance;
                out.push_back(origin);
            }
            continue;
        }
        const double new_lo = std::max(lo, (double(v.transmittance) - eps - origin.transmittance) / dz);
        const double new_hi = std::min(hi, (double(v.transmittance) + eps - origin.transmittance) / dz);
        if (new_lo <= new_hi) {
            lo = new_lo, hi = new_hi, reach = v.depth;
            continue;
        }
        close_segment();
        --j; // this vertex starts the next segment's constraints
    }
    if (reach > origin.depth) close_segment();
}
/// exp(-omega), with no call where it is 0: expf rounds to +0 for arguments below ln(2^-150) =
/// -103.97, and its underflow path (a helper that sets errno) took 5% of a 100M-segment build,
/// whose dense texels reach omega in the hundreds. The same bits as std::exp(-omega) for every omega
/// with glibc's expf, or any expf correctly rounded to nearest (exp(-104) is below 2^-150); the
/// tests check it on the platform they run on.
inline float exact_transmittance(float omega) noexcept { return omega >= 104.0f ? 0.0f : std::exp(-omega); }

/// The exact transmittance function of one texel as vertices: T steps down at each fragment's depth
/// (`depths` sorted, `optical_depths` the optical depth behind each), two vertices a step.
inline void exact_steps(std::span<const float> depths, std::span<const float> optical_depths, std::vector<transmittance_vertex>& out) {
    out.clear();
    out.reserve(2 * depths.size());
    float before = 1.0f;
    for (std::size_t i = 0; i < depths.size(); ++i) {
        const float after = exact_transmittance(optical_depths[i]);
        out.push_back({depths[i], before});
        out.push_back({depths[i], after});
        before = after;
    }
}

/// A piecewise-linear function's value at `depth`: 1 up to its first vertex (continuous from the
/// left at steps, as the exact map is), linear between vertices, the last one's beyond.
inline float transmittance_at(std::span<const transmittance_vertex> v, float depth) noexcept {
    const auto after = std::lower_bound(v.begin(), v.end(), depth, [](const transmittance_vertex& a, float d) { return a.depth < d; });
    if (after == v.begin()) return 1.0f;
    const auto& a = *(after - 1);
    if (after == v.end()) return a.transmittance;
    const float t = (depth - a.depth) / (after->depth - a.depth);
    return a.transmittance + t * (after->transmittance - a.transmittance);
}
} // namespace detail

/// A deep shadow map compressed to piecewise-linear transmittance functions within a tolerance.
class compressed_deep_shadow_map : public map_queries<compressed_deep_shadow_map> {
public:
    /// Compresses every texel of `exact` so that |T_compressed - T_exact| <= tolerance at every depth.
    compressed_deep_shadow_map(const deep_shadow_map& exact, float tolerance, const execution& exec = {})
        : light_(exact.light()), tolerance_(checked(tolerance)), fragments_(exact.fragment_count()), lists_(detail::map_tiling(exact.resolution(), tile_size)) {
        std::vector<scratch> slots(parallel_slots(lists_.tiling().tile_count(), exec));
        parallel_for_slots(lists_.tiling().tile_count(), exec, [&](unsigned slot, std::size_t t) {
            auto& s = slots[slot];
            build_tile(t, s, [&](std::size_t i) {
                const int w = lists_.tiling().width(t);
                const int x = lists_.tiling().x0(t) + int(i % std::size_t(w)), y = lists_.tiling().y0(t) + int(i / std::size_t(w));
                detail::exact_steps(exact.depths(x, y), exact.optical_depths(x, y), s.steps);
            });
        });
    }

    /// Streams `model`'s fragments tile by tile, compressing each texel's exact function as it is
    /// made (deep_shadow_map's streamed build, then Lokovic & Veach's compression): the same map as
    /// compressing deep_shadow_map(model, light, options), without ever holding it. Peak memory is
    /// this map plus one tile's fragments a thread; `workspace`, where given, keeps the working memory
    /// for the next build. Throws argument_error for a tolerance outside (0, 1) or bad options.
    compressed_deep_shadow_map(const hair_model& model, const light_space& light, float tolerance, const raster_options& options = {},
                               const build_progress& progress = {}, streamed_workspace* workspace = nullptr)
        : light_(light), tolerance_(checked(tolerance)), lists_(detail::map_tiling(light.resolution(), detail::checked_tile_size(options))) {
        streamed_workspace own;
        std::vector<scratch> slots(detail::streamed_slots(light, options));
        std::atomic<std::size_t> fragments{0};
        detail::stream_tiles(workspace ? *workspace : own, model, light, options, progress, [&](unsigned slot, std::size_t t, const detail::grouped_tile& tile) {
            auto& s = slots[slot];
            build_tile(t, s, [&](std::size_t i) {
                const auto in = tile.texel(i);
                s.depths.resize(in.size()), s.optical_depths.resize(in.size());
                detail::sort_texel(in, s.order, s.depths.data(), s.optical_depths.data());
                detail::exact_steps(s.depths, s.optical_depths, s.steps);
            });
            fragments.fetch_add(tile.fragments.size(), std::memory_order_relaxed);
        });
        fragments_ = fragments.load();
    }

    const light_space& light() const noexcept { return light_; }
    float tolerance() const noexcept { return tolerance_; }
    /// Vertices of texel (x, y)'s function.
    std::span<const transmittance_vertex> vertices(int x, int y) const noexcept { return lists_.list(x, y); }
    /// Transmittance at `depth` in texel (x, y), continuous from the left at steps as the exact map is.
    float transmittance(int x, int y, float depth) const noexcept { return detail::transmittance_at(vertices(x, y), depth); }
    /// -ln of the compressed transmittance, so that queries filter it like every other map.
    float optical_depth(int x, int y, float depth) const noexcept { return -std::log(std::max(transmittance(x, y, depth), 1e-30f)); }
    using map_queries<compressed_deep_shadow_map>::transmittance;
    std::size_t vertex_count() const noexcept { return lists_.size(); }
    /// The exact map's fragments that the functions were made from.
    std::size_t fragment_count() const noexcept { return fragments_; }
    std::size_t memory_bytes() const noexcept { return lists_.memory_bytes(); }

private:
    static constexpr int tile_size = 64;
    struct scratch {
        detail::depth_order order;
        std::vector<float> depths, optical_depths;
        std::vector<transmittance_vertex> steps, vertices; ///< a texel's exact steps; the tile's compressed functions
        std::vector<std::uint64_t> lengths;
    };

    static float checked(float tolerance) {
        if (!(tolerance > 0.0f && tolerance < 1.0f)) throw argument_error("compression tolerance must be in (0, 1)");
        return tolerance;
    }

    /// Compresses each texel of tile t (exact_steps_of(i) leaves texel i's steps in s.steps) and
    /// stores the tile.
    template <class ExactSteps>
    void build_tile(std::size_t t, scratch& s, ExactSteps&& exact_steps_of) {
        const std::size_t texels = std::size_t(lists_.tiling().width(t)) * std::size_t(lists_.tiling().height(t));
        s.vertices.clear();
        s.lengths.resize(texels);
        for (std::size_t i = 0; i < texels; ++i) {
            const std::size_t before = s.vertices.size();
            exact_steps_of(i);
            detail::compress_function(s.steps, tolerance_, s.vertices);
            s.lengths[i] = s.vertices.size() - before;
        }
        lists_.write_tile(t, s.lengths, [&](std::vector<transmittance_vertex>& block, std::size_t) { std::copy(s.vertices.begin(), s.vertices.end(), block.begin()); });
    }

    light_space light_;
    float tolerance_;
    std::size_t fragments_ = 0;
    detail::tile_lists<transmittance_vertex> lists_;
};

} // namespace hairshadow
