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
    /// texels across each segment with a Gaussian profile, instead of the aliased line rule. 0 = off;
    /// otherwise at least 2, below which texel-centre samples of the profile alias.
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
/// Returns false, leaving out.a == out.b, when nothing of it is left to draw.
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
    out.a = out.b = fixed_point{0, 0}; // marks the segment empty until it is known to have length
    if (!clip(d0 - lo, d1 - lo) || !clip(hi - d0, hi - d1)) return false;
    if (s0 > 0.0f || s1 < 1.0f) {
        const glm::vec3 q0 = p0 + (p1 - p0) * s0, q1 = p0 + (p1 - p0) * s1;
        const float u0 = t0 + (t1 - t0) * s0, u1 = t0 + (t1 - t0) * s1;
        const float v0 = o0 + (o1 - o0) * s0, v1 = o0 + (o1 - o0) * s1;
        p0 = q0, p1 = q1, t0 = u0, t1 = u1, o0 = v0, o1 = v1;
    }
    light_point a = ls.project(p0), b = ls.project(p1);
    // Clip to a guard band of +-2^20 texels in window space (perspective lights can throw points
    // near the near plane far off the map), keeping the fixed-point line rule free of overflow.
    // Attributes at a clipped end are interpolated perspective-correctly, as GL would.
    const float guard = float(1 << 20);
    if (!(std::abs(a.window.x) <= guard && std::abs(a.window.y) <= guard && std::abs(b.window.x) <= guard && std::abs(b.window.y) <= guard)) {
        double lo_s = 0.0, hi_s = 1.0;
        for (int axis = 0; axis < 2; ++axis) {
            const double from = a.window[axis], delta = double(b.window[axis]) - from;
            for (const double limit : {-double(guard), double(guard)}) {
                const bool upper = limit > 0;
                if (delta == 0.0) {
                    if (upper ? from > limit : from < limit) return false;
                    continue;
                }
                const double s = (limit - from) / delta;
                if ((delta > 0) == upper) hi_s = std::min(hi_s, s);
                else lo_s = std::max(lo_s, s);
            }
        }
        if (!(lo_s < hi_s)) return false;
        const light_point a0 = a, b0 = b;
        auto at = [&](double s, float fa, float fb) {
            const double ia = 1.0 / a0.w, ib = 1.0 / b0.w, inv = (1.0 - s) * ia + s * ib;
            return float(((1.0 - s) * fa * ia + s * fb * ib) / inv);
        };
        auto end = [&](double s) {
            const double ia = 1.0 / a0.w, ib = 1.0 / b0.w;
            return light_point{glm::vec2(float(a0.window.x + s * (double(b0.window.x) - a0.window.x)),
                                         float(a0.window.y + s * (double(b0.window.y) - a0.window.y))),
                               at(s, a0.depth, b0.depth), float(1.0 / ((1.0 - s) * ia + s * ib))};
        };
        const float t_lo = at(lo_s, t0, t1), t_hi = at(hi_s, t0, t1), o_lo = at(lo_s, o0, o1), o_hi = at(hi_s, o0, o1);
        a = end(lo_s), b = end(hi_s);
        t0 = t_lo, t1 = t_hi, o0 = o_lo, o1 = o_hi;
    }
    out = {{snap(a.window.x), snap(a.window.y)}, {snap(b.window.x), snap(b.window.y)}, a.depth, b.depth, 1.0f / a.w, 1.0f / b.w,
           t0, t1, o0, o1};
    return !(out.a == out.b);
}

/// Interpolates the segment's attributes at window-space parameter t (perspective-correct, as GL does
/// for line varyings) and returns the fragment.
HAIRSHADOW_ALWAYS_INLINE inline fragment shade_fragment(const light_space& ls, const raster_options& opt, const prepared_segment& s, float t, float weight) {
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
    return {depth, alpha > 0.0f ? std::min(alpha, HAIRSHADOW_ALPHA_MAX) : 0.0f}; // NaN gives 0
}

/// Window-space parameter of the texel centre (x, y) along a -> b, as in GL's line interpolation.
HAIRSHADOW_ALWAYS_INLINE inline float line_parameter(const prepared_segment& s, int x, int y) {
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

/// Rasterises hair models into light-space fragments, keeping its working memory between calls so
/// that a renderer rebuilding its maps every frame touches no new pages. Fragments follow the GL line
/// rule (or the wide-line filter); a fragment's alpha is the strand's opacity times the share of the
/// texel its thickness covers (thickness / texel footprint, at most 1), or the fixed alpha; either is
/// clamped to HAIRSHADOW_ALPHA_MAX.
class rasterizer {
public:
    /// Throws argument_error for a bad alpha, wide-line width or tile size.
    explicit rasterizer(const raster_options& options = {}) : opt_(options) {
        if (opt_.fixed_alpha && !(*opt_.fixed_alpha >= 0.0f && *opt_.fixed_alpha <= 1.0f))
            throw argument_error("fixed alpha must be in [0, 1]");
        if (!(opt_.wide_line_width == 0.0f || (opt_.wide_line_width >= 2.0f && opt_.wide_line_width <= 64.0f)))
            throw argument_error("wide line width must be 0 (off) or in [2, 64] texels");
        if (opt_.tile_size < 8 || opt_.tile_size > 1024) throw argument_error("tile size must be in [8, 1024]");
    }

    const raster_options& options() const noexcept { return opt_; }

    /// Rasterises every segment of `model` into `light`'s map. The result stays valid until the next
    /// call (move it out to keep it).
    fragment_buffer& operator()(const hair_model& model, const light_space& light) {
        prepare(model, light);
        bin(light.resolution());
        fill(light);
        return out_;
    }

private:
    static constexpr std::size_t chunks = 64; // fixed, so that binning does not depend on the thread count

    // 1. Project and snap every segment, strand by strand.
    void prepare(const hair_model& model, const light_space& light) {
        first_segment_.assign(model.strand_count() + 1, 0);
        for (std::size_t s = 0; s < model.strand_count(); ++s)
            first_segment_[s + 1] = first_segment_[s] + (model.strand_size(s) > 1 ? model.strand_size(s) - 1 : 0);
        const std::size_t count = first_segment_.back();
        if (count > std::numeric_limits<std::uint32_t>::max()) throw argument_error("more than 2^32 segments");
        segments_.resize(count);
        // Raw pointers: stores through a member vector would make the compiler reload its data pointer.
        detail::prepared_segment* out = segments_.data();
        const std::size_t* first = first_segment_.data();
        parallel_for(model.strand_count(), opt_.exec, [&model, &light, out, first](std::size_t s) {
            const std::size_t p0 = model.strand_offsets[s];
            for (std::size_t i = 0; i + 1 < model.strand_size(s); ++i) {
                const std::size_t p = p0 + i;
                detail::prepare_segment(light, model.points[p], model.points[p + 1], model.thickness_at(p), model.thickness_at(p + 1),
                                        1.0f - model.transparency_at(p), 1.0f - model.transparency_at(p + 1), out[first[s] + i]);
            }
        }, 256);
    }

    // 2. Bin segments into tiles. Each of a fixed number of chunks of the segment range counts, then
    // writes, its segments per tile, so every tile's list is in segment order for any thread count.
    void bin(int res) {
        res_ = res;
        tiles_x_ = (res + opt_.tile_size - 1) / opt_.tile_size;
        const std::size_t tile_count = std::size_t(tiles_x_) * std::size_t(tiles_x_);
        const std::size_t segment_count = segments_.size();
        const std::size_t chunk_size = (segment_count + chunks - 1) / chunks;
        // Texels around the segment that it may touch, in sub-pixel units.
        const auto reach = std::int64_t(std::ceil((1.0 + 0.5 * double(opt_.wide_line_width)) * double(subpixel_scale)));
        auto for_each_tile_of_chunk = [&](std::size_t c, auto&& visit) {
            const std::size_t begin = c * chunk_size, end = std::min(segment_count, begin + chunk_size);
            for (std::size_t seg = begin; seg < end; ++seg) {
                const auto& s = segments_[seg];
                if (s.a == s.b) continue; // nothing to draw (clipped away or zero length)
                visit_tiles(s, reach, [&](std::size_t t) HAIRSHADOW_ALWAYS_INLINE { visit(seg, t); });
            }
        };
        cursor_.assign(chunks * tile_count, 0);
        parallel_for(chunks, opt_.exec, [&](std::size_t c) {
            for_each_tile_of_chunk(c, [&](std::size_t, std::size_t t) { ++cursor_[c * tile_count + t]; });
        });
        tile_begin_.resize(tile_count + 1);
        std::uint64_t total = 0;
        for (std::size_t t = 0; t < tile_count; ++t) {
            tile_begin_[t] = total;
            for (std::size_t c = 0; c < chunks; ++c) {
                const std::uint64_t n = cursor_[c * tile_count + t];
                cursor_[c * tile_count + t] = total;
                total += n;
            }
        }
        tile_begin_[tile_count] = total;
        binned_.resize(total);
        parallel_for(chunks, opt_.exec, [&](std::size_t c) {
            for_each_tile_of_chunk(c, [&](std::size_t seg, std::size_t t) { binned_[cursor_[c * tile_count + t]++] = std::uint32_t(seg); });
        });
    }

    /// Calls visit(tile) for each tile within `reach` (sub-pixel units) of the segment; a long diagonal
    /// segment visits O(its length) tiles rather than its whole bounding box.
    template <class Visit>
    HAIRSHADOW_ALWAYS_INLINE void visit_tiles(const detail::prepared_segment& s, std::int64_t reach, Visit&& visit) const {
        // Texel bounds of the segment plus its reach; arithmetic shifts floor negative values.
        const std::int64_t lo_x = (std::min(s.a.x, s.b.x) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t hi_x = (std::max(s.a.x, s.b.x) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t lo_y = (std::min(s.a.y, s.b.y) - reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        const std::int64_t hi_y = (std::max(s.a.y, s.b.y) + reach) >> HAIRSHADOW_SUBPIXEL_BITS;
        if (hi_x < 0 || hi_y < 0 || lo_x >= res_ || lo_y >= res_) return;
        const int tile = opt_.tile_size;
        const int tx0 = int(std::max<std::int64_t>(lo_x, 0)) / tile, tx1 = int(std::min<std::int64_t>(hi_x, res_ - 1)) / tile;
        const int ty0 = int(std::max<std::int64_t>(lo_y, 0)) / tile, ty1 = int(std::min<std::int64_t>(hi_y, res_ - 1)) / tile;
        if (ty0 == ty1 || tx0 == tx1) { // most hair segments: one row or column of tiles, as the box says
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) visit(std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx));
            return;
        }
        // A segment across several rows and columns: per row of tiles, only the columns that the
        // segment's piece in that row (widened by reach) spans.
        const double scale = 1.0 / double(subpixel_scale), r = double(reach) * scale;
        const double ax = double(s.a.x) * scale, ay = double(s.a.y) * scale, bx = double(s.b.x) * scale, by = double(s.b.y) * scale;
        for (int ty = ty0; ty <= ty1; ++ty) {
            const double band_lo = double(ty * tile) - r, band_hi = double((ty + 1) * tile) + r;
            const double u = (band_lo - ay) / (by - ay), v = (band_hi - ay) / (by - ay); // by != ay: the box spans rows
            const double s0 = std::max(0.0, std::min(u, v)), s1 = std::min(1.0, std::max(u, v));
            if (s0 > s1) continue;
            const double x0 = ax + s0 * (bx - ax), x1 = ax + s1 * (bx - ax);
            const int c0 = std::max(tx0, int(std::floor((std::min(x0, x1) - r) / tile)));
            const int c1 = std::min(tx1, int(std::floor((std::max(x0, x1) + r) / tile)));
            for (int tx = c0; tx <= c1; ++tx) visit(std::size_t(ty) * std::size_t(tiles_x_) + std::size_t(tx));
        }
    }

    texel_rect tile_rect(std::size_t t) const noexcept {
        const int tile = opt_.tile_size;
        const int tx = int(t % std::size_t(tiles_x_)), ty = int(t / std::size_t(tiles_x_));
        return {tx * tile, ty * tile, std::min(res_, (tx + 1) * tile), std::min(res_, (ty + 1) * tile)};
    }

    /// Calls visit(segment, x, y, parameter, weight) for every fragment of tile t's segments, in segment
    /// order; thin lines pass parameter -1 (computed only when needed).
    template <class Visit>
    HAIRSHADOW_ALWAYS_INLINE void for_each_fragment(std::size_t t, const texel_rect& rect, Visit&& visit) const {
        constexpr std::uint64_t lookahead = 8; // a tile's segments lie scattered in memory: fetch ahead
        const std::uint64_t end = tile_begin_[t + 1];
        for (std::uint64_t i = tile_begin_[t]; i < end; ++i) {
#if defined(__GNUC__)
            if (i + lookahead < end) __builtin_prefetch(&segments_[binned_[i + lookahead]]);
#endif
            const auto& s = segments_[binned_[i]];
            if (opt_.wide_line_width > 0.0f)
                detail::rasterize_wide_line(s, opt_.wide_line_width, rect, [&](int x, int y, float param, float weight) { visit(s, x, y, param, weight); });
            else
                rasterize_line(s.a, s.b, rect, [&](int x, int y) HAIRSHADOW_ALWAYS_INLINE { visit(s, x, y, -1.0f, 1.0f); });
        }
    }

    // 3. Rasterise each tile into its own buffer (kept between calls) while counting every texel's
    // fragments; then, once the offsets are known, scatter each tile's fragments to their texels in
    // the order they were made, which is segment order.
    void fill(const light_space& light) {
        const std::size_t tile_count = std::size_t(tiles_x_) * std::size_t(tiles_x_);
        const std::size_t texels = std::size_t(res_) * std::size_t(res_);
        auto& offsets = out_.offsets_;
        offsets.assign(texels + 1, 0);
        tile_fragments_.resize(tile_count);
        parallel_for(tile_count, opt_.exec, [&](std::size_t t) {
            const texel_rect rect = tile_rect(t);
            // Work on a local vector: neighbouring tiles' vector headers share cache lines.
            auto made = std::move(tile_fragments_[t]);
            made.clear();
            for_each_fragment(t, rect, [&](const detail::prepared_segment& s, int x, int y, float param, float weight) HAIRSHADOW_ALWAYS_INLINE {
                if (param < 0.0f) param = detail::line_parameter(s, x, y);
                const std::size_t texel = std::size_t(y) * std::size_t(res_) + std::size_t(x);
                ++offsets[texel + 1];
                made.push_back({std::uint32_t(texel), detail::shade_fragment(light, opt_, s, param, weight)});
            });
            tile_fragments_[t] = std::move(made);
        });
        for (std::size_t i = 0; i < texels; ++i) offsets[i + 1] += offsets[i];
        out_.resolution_ = res_;
        out_.fragments_.resize(offsets.back());
        parallel_for(tile_count, opt_.exec, [&](std::size_t t) {
            const auto& made = tile_fragments_[t];
            if (made.empty()) return;
            const texel_rect rect = tile_rect(t);
            const std::size_t w = std::size_t(rect.x1 - rect.x0);
            std::vector<std::uint64_t> cursor(w * std::size_t(rect.y1 - rect.y0));
            for (int y = rect.y0; y < rect.y1; ++y)
                for (int x = rect.x0; x < rect.x1; ++x)
                    cursor[std::size_t(y - rect.y0) * w + std::size_t(x - rect.x0)] = offsets[std::size_t(y) * std::size_t(res_) + std::size_t(x)];
            for (const auto& m : made) {
                const std::size_t x = m.texel % std::size_t(res_), y = m.texel / std::size_t(res_);
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
    int res_ = 0, tiles_x_ = 0;
    std::vector<detail::prepared_segment> segments_;
    std::vector<std::size_t> first_segment_;
    std::vector<std::uint64_t> cursor_, tile_begin_;
    std::vector<std::uint32_t> binned_;
    std::vector<std::vector<placed_fragment>> tile_fragments_;
};

/// Rasterises every segment of `model` into `light`'s map (a one-shot rasterizer).
inline fragment_buffer rasterize(const hair_model& model, const light_space& light, const raster_options& options = {}) {
    rasterizer r(options);
    return std::move(r(model, light));
}

} // namespace hairshadow
