#pragma once
/// @file
/// Rasterises a hair model's segments into light-space fragments (texel, depth, alpha), in parallel
/// tiles, with per-texel output identical for any thread count.

#include <hairshadow/config.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/line_rule.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace hairshadow {

/// How segments become fragments.
struct raster_options {
    execution exec{};
    /// When set, every fragment gets this alpha instead of its coverage (`--alpha A`).
    std::optional<float> fixed_alpha{};
    /// Pre-filtered wide lines (Mertens et al. 2004, section 3.4): a screen-aligned band of this many
    /// texels across each segment with a Gaussian profile, instead of the aliased line rule. 0 = off.
    float wide_line_width = 0.0f;
    /// Perspective lights: weight coverage by reciprocal depth (Mertens et al. 2004, section 3.4), i.e.
    /// divide the thickness by the texel's footprint at the fragment's depth rather than at mid-range.
    bool depth_weighting = true;
    /// Side of the square tiles that are rasterised in parallel, in texels.
    int tile_size = 32;
};

namespace detail {

/// A segment ready for the line rule: snapped endpoints and the attributes to interpolate.
struct prepared_segment {
    fixed_point a, b;
    float depth_a, depth_b;      // linear depth
    float inv_w_a, inv_w_b;      // 1/w for perspective-correct interpolation (1 for orthographic)
    float thickness_a, thickness_b;
    float opacity_a, opacity_b;
};

inline std::int64_t snap(float window) noexcept { return std::llround(double(window) * double(subpixel_scale)); }

/// Clips the segment p0 -> p1 to the light's near and far planes (linear in view space) and projects it.
/// Returns false when nothing of it is left.
inline bool prepare_segment(const light_space& ls, glm::vec3 p0, glm::vec3 p1, float t0, float t1, float o0, float o1,
                            prepared_segment& out) {
    const glm::mat4& view = ls.view();
    float d0 = -(view * glm::vec4(p0, 1.0f)).z, d1 = -(view * glm::vec4(p1, 1.0f)).z;
    const float lo = ls.near_plane(), hi = ls.far_plane();
    float s0 = 0.0f, s1 = 1.0f; // kept part of the segment, as parameters
    auto clip = [&](float f0, float f1) { // keep f >= 0
        if (f0 < 0 && f1 < 0) return false;
        if (f0 < 0) s0 = std::max(s0, f0 / (f0 - f1));
        if (f1 < 0) s1 = std::min(s1, f0 / (f0 - f1));
        return s0 <= s1;
    };
    if (!clip(d0 - lo, d1 - lo) || !clip(hi - d0, hi - d1)) return false;
    if (s0 > 0.0f || s1 < 1.0f) {
        const glm::vec3 q0 = p0 + (p1 - p0) * s0, q1 = p0 + (p1 - p0) * s1;
        const float u0 = t0 + (t1 - t0) * s0, u1 = t0 + (t1 - t0) * s1;
        const float v0 = o0 + (o1 - o0) * s0, v1 = o0 + (o1 - o0) * s1;
        p0 = q0, p1 = q1, t0 = u0, t1 = u1, o0 = v0, o1 = v1;
    }
    const light_point a = ls.project(p0), b = ls.project(p1);
    // Keep coordinates well inside the fixed-point range; such far-off points only arise for
    // perspective lights and lie outside the map anyway.
    const float guard = float(1 << 24);
    if (!(std::abs(a.window.x) < guard && std::abs(a.window.y) < guard && std::abs(b.window.x) < guard && std::abs(b.window.y) < guard))
        return false;
    out = {{snap(a.window.x), snap(a.window.y)}, {snap(b.window.x), snap(b.window.y)}, a.depth, b.depth, 1.0f / a.w, 1.0f / b.w,
           t0, t1, o0, o1};
    return !(out.a == out.b);
}

/// Interpolates the segment's attributes at window-space parameter t (perspective-correct, as GL does
/// for line varyings) and returns the fragment.
inline fragment shade_fragment(const light_space& ls, const raster_options& opt, const prepared_segment& s, float t, float weight) {
    const float wa = (1.0f - t) * s.inv_w_a, wb = t * s.inv_w_b;
    const float k = 1.0f / (wa + wb);
    const float depth = (wa * s.depth_a + wb * s.depth_b) * k;
    float alpha;
    if (opt.fixed_alpha) {
        alpha = *opt.fixed_alpha * weight;
    } else {
        const float thickness = (wa * s.thickness_a + wb * s.thickness_b) * k;
        const float opacity = (wa * s.opacity_a + wb * s.opacity_b) * k;
        const float footprint = ls.texel_size(opt.depth_weighting ? depth : 0.5f);
        alpha = opacity * std::min(1.0f, thickness / footprint) * weight;
    }
    return {depth, std::clamp(alpha, 0.0f, HAIRSHADOW_ALPHA_MAX)};
}

/// Window-space parameter of the texel centre (x, y) along a -> b, as in GL's line interpolation.
inline float line_parameter(const prepared_segment& s, int x, int y) {
    const double ax = double(s.a.x) / subpixel_scale, ay = double(s.a.y) / subpixel_scale;
    const double dx = double(s.b.x - s.a.x) / subpixel_scale, dy = double(s.b.y - s.a.y) / subpixel_scale;
    const double t = ((x + 0.5 - ax) * dx + (y + 0.5 - ay) * dy) / (dx * dx + dy * dy);
    return float(std::clamp(t, 0.0, 1.0));
}

/// Pre-filtered wide line: texel centres within half the width of the segment's axis, between its
/// ends, weighted by a Gaussian (sigma = width / 4) truncated at the band's edge and normalised so
/// that it integrates to one texel across the band.
template <class Emit>
void rasterize_wide_line(const prepared_segment& s, float width, const texel_rect& clip, Emit&& emit) {
    const double ax = double(s.a.x) / subpixel_scale, ay = double(s.a.y) / subpixel_scale;
    const double dx = double(s.b.x - s.a.x) / subpixel_scale, dy = double(s.b.y - s.a.y) / subpixel_scale;
    const double len2 = dx * dx + dy * dy, len = std::sqrt(len2);
    const double half = 0.5 * width, sigma = 0.25 * width;
    const double norm = 1.0 / (sigma * std::sqrt(2.0 * std::numbers::pi) * std::erf(half / (sigma * std::numbers::sqrt2)));
    const int x0 = std::max(clip.x0, int(std::floor(std::min(ax, ax + dx) - half))), x1 = std::min(clip.x1, int(std::ceil(std::max(ax, ax + dx) + half)) + 1);
    const int y0 = std::max(clip.y0, int(std::floor(std::min(ay, ay + dy) - half))), y1 = std::min(clip.y1, int(std::ceil(std::max(ay, ay + dy) + half)) + 1);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const double px = x + 0.5 - ax, py = y + 0.5 - ay;
            const double t = (px * dx + py * dy) / len2;
            const double across = (px * dy - py * dx) / len;
            if (t >= 0.0 && t < 1.0 && std::abs(across) < half)
                emit(x, y, float(t), float(norm * std::exp(-across * across / (2.0 * sigma * sigma))));
        }
}

} // namespace detail

/// Rasterises every segment of `model` into `light`'s map. Fragments follow the GL line rule (or the
/// wide-line filter); a fragment's alpha is the strand's opacity times the share of the texel its
/// thickness covers (thickness / texel footprint, at most 1), or the fixed alpha; either is clamped
/// to HAIRSHADOW_ALPHA_MAX. Throws argument_error for a bad alpha, width or tile size.
inline fragment_buffer rasterize(const hair_model& model, const light_space& light, const raster_options& opt = {}) {
    if (opt.fixed_alpha && !(*opt.fixed_alpha >= 0.0f && *opt.fixed_alpha <= 1.0f))
        throw argument_error("fixed alpha must be in [0, 1]");
    if (!(opt.wide_line_width >= 0.0f && opt.wide_line_width <= 64.0f)) throw argument_error("wide line width must be in [0, 64] texels");
    if (opt.tile_size < 8 || opt.tile_size > 1024) throw argument_error("tile size must be in [8, 1024]");
    const int res = light.resolution();
    const int tile = opt.tile_size;
    const int tiles_x = (res + tile - 1) / tile;
    const std::size_t tile_count = std::size_t(tiles_x) * std::size_t(tiles_x);

    // 1. Prepare segments (project and snap), strand by strand.
    std::vector<std::size_t> first_segment(model.strand_count() + 1, 0);
    for (std::size_t s = 0; s < model.strand_count(); ++s)
        first_segment[s + 1] = first_segment[s] + (model.strand_size(s) > 1 ? model.strand_size(s) - 1 : 0);
    const std::size_t segment_count = first_segment.back();
    if (segment_count > std::numeric_limits<std::uint32_t>::max()) throw argument_error("more than 2^32 segments");
    std::vector<detail::prepared_segment> segments(segment_count);
    std::vector<unsigned char> live(segment_count, 0);
    parallel_for(model.strand_count(), opt.exec, [&](std::size_t s) {
        const std::size_t p0 = model.strand_offsets[s];
        for (std::size_t i = 0; i + 1 < model.strand_size(s); ++i) {
            const std::size_t p = p0 + i, seg = first_segment[s] + i;
            live[seg] = detail::prepare_segment(light, model.points[p], model.points[p + 1], model.thickness_at(p), model.thickness_at(p + 1),
                                                1.0f - model.transparency_at(p), 1.0f - model.transparency_at(p + 1), segments[seg]);
        }
    }, 256);

    // 2. Bin segments into tiles. The segment range is cut into a fixed number of chunks (not one per
    // thread), so the per-tile lists come out in segment order for any thread count.
    const double reach = 1.0 + 0.5 * opt.wide_line_width;
    auto tile_range = [&](const detail::prepared_segment& s, int& tx0, int& ty0, int& tx1, int& ty1) {
        const double lo_x = double(std::min(s.a.x, s.b.x)) / subpixel_scale - reach, hi_x = double(std::max(s.a.x, s.b.x)) / subpixel_scale + reach;
        const double lo_y = double(std::min(s.a.y, s.b.y)) / subpixel_scale - reach, hi_y = double(std::max(s.a.y, s.b.y)) / subpixel_scale + reach;
        if (hi_x < 0 || hi_y < 0 || lo_x >= res || lo_y >= res) return false;
        tx0 = std::max(0, int(std::floor(lo_x)) / tile), ty0 = std::max(0, int(std::floor(lo_y)) / tile);
        tx1 = std::min(tiles_x - 1, int(std::min(hi_x, double(res - 1))) / tile), ty1 = std::min(tiles_x - 1, int(std::min(hi_y, double(res - 1))) / tile);
        return true;
    };
    constexpr std::size_t chunks = 64;
    const std::size_t chunk_size = (segment_count + chunks - 1) / chunks;
    std::vector<std::uint32_t> chunk_counts(chunks * tile_count, 0);
    auto for_each_tile_of_chunk = [&](std::size_t c, auto&& visit) {
        const std::size_t begin = c * chunk_size, end = std::min(segment_count, begin + chunk_size);
        for (std::size_t seg = begin; seg < end; ++seg) {
            int tx0, ty0, tx1, ty1;
            if (!live[seg] || !tile_range(segments[seg], tx0, ty0, tx1, ty1)) continue;
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) visit(seg, std::size_t(ty) * tiles_x + std::size_t(tx));
        }
    };
    parallel_for(chunks, opt.exec, [&](std::size_t c) {
        for_each_tile_of_chunk(c, [&](std::size_t, std::size_t t) { ++chunk_counts[c * tile_count + t]; });
    });
    std::vector<std::uint64_t> tile_begin(tile_count + 1, 0);
    std::vector<std::uint64_t> chunk_cursor(chunks * tile_count);
    {
        std::uint64_t total = 0;
        for (std::size_t t = 0; t < tile_count; ++t) {
            tile_begin[t] = total;
            for (std::size_t c = 0; c < chunks; ++c) {
                chunk_cursor[c * tile_count + t] = total;
                total += chunk_counts[c * tile_count + t];
            }
        }
        tile_begin[tile_count] = total;
    }
    chunk_counts = {};
    std::vector<std::uint32_t> binned(tile_begin[tile_count]);
    parallel_for(chunks, opt.exec, [&](std::size_t c) {
        for_each_tile_of_chunk(c, [&](std::size_t seg, std::size_t t) { binned[chunk_cursor[c * tile_count + t]++] = std::uint32_t(seg); });
    });
    chunk_cursor = {};

    // 3. Rasterise each tile; sort its fragments by texel, keeping segment order within a texel.
    std::vector<std::uint32_t> texel_counts(std::size_t(res) * std::size_t(res), 0);
    std::vector<std::vector<fragment>> tile_fragments(tile_count);
    parallel_for(tile_count, opt.exec, [&](std::size_t t) {
        const int tx = int(t % std::size_t(tiles_x)), ty = int(t / std::size_t(tiles_x));
        const texel_rect rect{tx * tile, ty * tile, std::min(res, (tx + 1) * tile), std::min(res, (ty + 1) * tile)};
        const int w = rect.x1 - rect.x0;
        struct tagged { std::uint32_t local; fragment f; };
        std::vector<tagged> raw;
        for (std::uint64_t i = tile_begin[t]; i < tile_begin[t + 1]; ++i) {
            const auto& s = segments[binned[i]];
            if (opt.wide_line_width > 0.0f) {
                detail::rasterize_wide_line(s, opt.wide_line_width, rect, [&](int x, int y, float param, float weight) {
                    raw.push_back({std::uint32_t((y - rect.y0) * w + (x - rect.x0)), detail::shade_fragment(light, opt, s, param, weight)});
                });
            } else {
                rasterize_line(s.a, s.b, rect, [&](int x, int y) {
                    raw.push_back({std::uint32_t((y - rect.y0) * w + (x - rect.x0)),
                                   detail::shade_fragment(light, opt, s, detail::line_parameter(s, x, y), 1.0f)});
                });
            }
        }
        if (raw.empty()) return;
        std::vector<std::uint32_t> start(std::size_t(w) * std::size_t(rect.y1 - rect.y0) + 1, 0);
        for (const auto& r : raw) ++start[r.local + 1];
        for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
        for (std::size_t i = 0; i + 1 < start.size(); ++i) {
            const int x = rect.x0 + int(i % std::size_t(w)), y = rect.y0 + int(i / std::size_t(w));
            texel_counts[std::size_t(y) * std::size_t(res) + std::size_t(x)] = start[i + 1] - start[i];
        }
        auto& sorted = tile_fragments[t];
        sorted.resize(raw.size());
        for (const auto& r : raw) sorted[start[r.local]++] = r.f;
    });
    binned = {};

    // 4. Gather the tiles into one row-major buffer.
    std::vector<std::uint64_t> offsets(std::size_t(res) * std::size_t(res) + 1, 0);
    for (std::size_t i = 0; i < texel_counts.size(); ++i) offsets[i + 1] = offsets[i] + texel_counts[i];
    texel_counts = {};
    std::vector<fragment> fragments(offsets.back());
    parallel_for(tile_count, opt.exec, [&](std::size_t t) {
        const auto& src = tile_fragments[t];
        if (src.empty()) return;
        const int tx = int(t % std::size_t(tiles_x)), ty = int(t / std::size_t(tiles_x));
        const int x0 = tx * tile, x1 = std::min(res, (tx + 1) * tile);
        std::size_t k = 0;
        for (int y = ty * tile; y < std::min(res, (ty + 1) * tile); ++y) {
            const std::size_t row = std::size_t(y) * std::size_t(res);
            const std::uint64_t begin = offsets[row + std::size_t(x0)], end = offsets[row + std::size_t(x1)];
            std::copy(src.begin() + std::ptrdiff_t(k), src.begin() + std::ptrdiff_t(k + (end - begin)), fragments.begin() + std::ptrdiff_t(begin));
            k += end - begin;
        }
        tile_fragments[t] = {};
    });
    return fragment_buffer(res, std::move(offsets), std::move(fragments));
}

} // namespace hairshadow
