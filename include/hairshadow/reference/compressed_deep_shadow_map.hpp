#pragma once
/// @file
/// Lokovic & Veach's compression of a deep shadow map: each texel's transmittance function becomes a
/// piecewise-linear function with as few vertices as the greedy algorithm of their section 4.2 allows
/// while staying within `tolerance` of the exact function at every depth.

#include <hairshadow/reference/deep_shadow_map.hpp>

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
/// The exact transmittance function of one texel as vertices: T steps down at each fragment's depth
/// (`depths` sorted, `optical_depths` the optical depth behind each), two vertices a step.
inline void exact_steps(std::span<const float> depths, std::span<const float> optical_depths, std::vector<transmittance_vertex>& out) {
    out.clear();
    out.reserve(2 * depths.size());
    float before = 1.0f;
    for (std::size_t i = 0; i < depths.size(); ++i) {
        const float after = std::exp(-optical_depths[i]);
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
        : light_(exact.light()), tolerance_(tolerance) {
        if (!(tolerance > 0.0f && tolerance < 1.0f)) throw argument_error("compression tolerance must be in (0, 1)");
        const int res = exact.resolution();
        const std::size_t texels = std::size_t(res) * std::size_t(res);
        std::vector<std::vector<transmittance_vertex>> per_texel(texels);
        parallel_for(texels, exec, [&](std::size_t t) {
            const int x = int(t % std::size_t(res)), y = int(t / std::size_t(res));
            const auto depths = exact.depths(x, y);
            if (depths.empty()) return;
            std::vector<transmittance_vertex> steps;
            detail::exact_steps(depths, exact.optical_depths(x, y), steps);
            detail::compress_function(steps, tolerance, per_texel[t]);
        }, 1024);
        offsets_.assign(texels + 1, 0);
        for (std::size_t t = 0; t < texels; ++t) offsets_[t + 1] = offsets_[t] + per_texel[t].size();
        vertices_.resize(offsets_.back());
        parallel_for(texels, exec, [&](std::size_t t) { std::copy(per_texel[t].begin(), per_texel[t].end(), vertices_.begin() + std::ptrdiff_t(offsets_[t])); }, 4096);
    }

    const light_space& light() const noexcept { return light_; }
    float tolerance() const noexcept { return tolerance_; }
    /// Vertices of texel (x, y)'s function.
    std::span<const transmittance_vertex> vertices(int x, int y) const noexcept {
        const std::size_t t = std::size_t(y) * std::size_t(light_.resolution()) + std::size_t(x);
        return {vertices_.data() + offsets_[t], std::size_t(offsets_[t + 1] - offsets_[t])};
    }
    /// Transmittance at `depth` in texel (x, y), continuous from the left at steps as the exact map is.
    float transmittance(int x, int y, float depth) const noexcept { return detail::transmittance_at(vertices(x, y), depth); }
    /// -ln of the compressed transmittance, so that queries filter it like every other map.
    float optical_depth(int x, int y, float depth) const noexcept { return -std::log(std::max(transmittance(x, y, depth), 1e-30f)); }
    using map_queries<compressed_deep_shadow_map>::transmittance;
    std::size_t vertex_count() const noexcept { return vertices_.size(); }
    std::size_t memory_bytes() const noexcept { return offsets_.size() * sizeof(std::uint64_t) + vertices_.size() * sizeof(transmittance_vertex); }

private:
    light_space light_;
    float tolerance_;
    std::vector<std::uint64_t> offsets_;
    std::vector<transmittance_vertex> vertices_;
};

} // namespace hairshadow
