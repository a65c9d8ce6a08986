#pragma once
/// @file
/// Segments ready for the line rule (clipped to the light's depth range and a guard band, projected,
/// snapped to sub-pixel fixed point), and the shading of their fragments: depth and alpha at a texel.

#include <hairshadow/config.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/line_rule.hpp>
#include <hairshadow/raster/raster_options.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace hairshadow::detail {

/// Where a segment lies for the line rule, in 24 bytes: what segment_bins keeps of every segment of a
/// map (millions, read from memory once per tile pass, so their size is time and memory).
struct segment_geometry {
    std::int32_t ax, ay, bx, by; ///< snapped window coordinates (1/subpixel_scale texels), inside the guard band
    float depth_a, depth_b;      ///< linear depth

    fixed_point a() const noexcept { return {ax, ay}; }
    fixed_point b() const noexcept { return {bx, by}; }
    /// Nothing to draw: clipped away, or of zero length.
    bool empty() const noexcept { return ax == bx && ay == by; }
};

/// A segment ready for the line rule and its fragments' shading.
/// Fragments a thin segment can give one tile of side `tile_size`: its length in texels along its
/// major axis plus 2 (one texel centre a column, or row, and the ends), at most the tile's side plus 1.
HAIRSHADOW_ALWAYS_INLINE inline std::uint64_t segment_fragment_bound(const segment_geometry& s, int tile_size) noexcept {
    const std::int64_t major = std::max(std::abs(std::int64_t(s.bx) - s.ax), std::abs(std::int64_t(s.by) - s.ay));
    return std::uint64_t(std::min<std::int64_t>((major >> HAIRSHADOW_SUBPIXEL_BITS) + 2, tile_size + 1));
}

/// The columns (rows, for a y-major segment) whose texel centres a thin segment may pass, from the
/// one before its first end's texel to the one after its last's, and its segment_fragment_bound.
struct fragment_lines {
    std::uint64_t bound = 0;
    bool x_major = false;
    std::int64_t first = 0, last = 0;
};
HAIRSHADOW_ALWAYS_INLINE inline fragment_lines fragment_lines_of(const segment_geometry& s, int tile_size) noexcept {
    const bool x_major = std::abs(std::int64_t(s.bx) - s.ax) >= std::abs(std::int64_t(s.by) - s.ay);
    const std::int64_t lo = x_major ? std::min(s.ax, s.bx) : std::min(s.ay, s.by), hi = x_major ? std::max(s.ax, s.bx) : std::max(s.ay, s.by);
    return {segment_fragment_bound(s, tile_size), x_major, (lo >> HAIRSHADOW_SUBPIXEL_BITS) - 1, (hi >> HAIRSHADOW_SUBPIXEL_BITS) + 1};
}

struct prepared_segment : segment_geometry {
    float inv_w_a, inv_w_b; ///< 1/w, for perspective-correct interpolation (1 for orthographic lights)
};

/// Thickness and opacity at a segment's two ends.
struct segment_attributes {
    float thickness_a, thickness_b, opacity_a, opacity_b;
};

/// Window coordinates of the guard band: +-2^20 texels keeps every snapped coordinate, and every
/// word of the fixed-point line rule (raster/line_rule.hpp, at up to 9 sub-pixel bits), inside 32 bits.
inline constexpr float guard_band = float(1 << 20);

/// Window coordinate to sub-pixel fixed point, rounding half away from zero (std::llround, without
/// its call into libm). x = window S is a float's 24 bits times a power of two, within the guard band,
/// so x +- 1/2 is exact in a double, and truncating it rounds x half away from zero.
HAIRSHADOW_ALWAYS_INLINE inline std::int32_t snap(float window) noexcept {
    const double x = double(window) * double(subpixel_scale);
    return std::int32_t(x + std::copysign(0.5, x));
}

/// A point seen from the light: its distance along the light's axis (for clipping) and projection.
struct projected_point {
    float distance;
    light_point projected;
};
HAIRSHADOW_ALWAYS_INLINE inline projected_point project_point(const light_space& ls, const glm::vec3& p) noexcept {
    const float distance = ls.distance_of(p);
    return {distance, ls.project(p, distance)};
}

/// a + (b - a) s: exact at s = 0, and exactly a wherever a == b, so that a strand of constant
/// thickness and opacity gives every fragment the same alpha.
HAIRSHADOW_ALWAYS_INLINE inline float lerp_exact(float a, float b, float s) noexcept { return a + rounded((b - a) * s); }

/// Clips the segment p0 -> p1 to the light's near and far planes (linear in view space) and to the
/// guard band, and projects it; `attributes` are updated to the clipped ends. `pp0` and `pp1` are the
/// ends' project_point, which a strand shares between its segments. Returns false, leaving `out`
/// empty, when nothing of it is left to draw.
HAIRSHADOW_ALWAYS_INLINE inline bool prepare_segment(const light_space& ls, glm::vec3 p0, glm::vec3 p1, const projected_point& pp0,
                                                     const projected_point& pp1, segment_attributes& attributes, prepared_segment& out) {
    out = {};
    const float d0 = pp0.distance, d1 = pp1.distance;
    const float lo = ls.near_plane(), hi = ls.far_plane();
    float s0 = 0.0f, s1 = 1.0f; // kept part of the segment, as parameters
    auto clip = [&](float f0, float f1) { // keep f >= 0
        if (!(f0 >= 0 || f1 >= 0)) return false; // both behind, or NaN
        if (f0 < 0) s0 = std::max(s0, f0 / (f0 - f1));
        if (f1 < 0) s1 = std::min(s1, f0 / (f0 - f1));
        return s0 <= s1;
    };
    if (!clip(d0 - lo, d1 - lo) || !clip(hi - d0, hi - d1)) return false;
    segment_attributes& at = attributes;
    light_point a = pp0.projected, b = pp1.projected;
    if (s0 > 0.0f || s1 < 1.0f) [[unlikely]] {
        const glm::vec3 q0 = p0 + (p1 - p0) * s0, q1 = p0 + (p1 - p0) * s1;
        at = {lerp_exact(at.thickness_a, at.thickness_b, s0), lerp_exact(at.thickness_a, at.thickness_b, s1),
              lerp_exact(at.opacity_a, at.opacity_b, s0), lerp_exact(at.opacity_a, at.opacity_b, s1)};
        a = ls.project(q0), b = ls.project(q1);
    }
    // Perspective lights can throw points near the near plane far off the map: clip to the guard
    // band in window space, with the attributes at a clipped end interpolated perspective-correctly,
    // as GL would. In float, every product rounded on its own, as compute/prepare does it on the GPU.
    // The parameter is a few ULP off, which can put a clipped end past the band (by about a texel
    // for an end at 2^24 texels): the ends are clamped to it, or the check below would drop the
    // whole segment.
    if (!(std::abs(a.window.x) <= guard_band && std::abs(a.window.y) <= guard_band && std::abs(b.window.x) <= guard_band &&
          std::abs(b.window.y) <= guard_band)) [[unlikely]] {
        float lo_s = 0.0f, hi_s = 1.0f;
        for (int axis = 0; axis < 2; ++axis) {
            const float from = a.window[axis], delta = b.window[axis] - from;
            if (!std::isfinite(delta)) return false; // ends beyond float's range: nothing sensible to draw
            for (const float limit : {-guard_band, guard_band}) {
                const bool upper = limit > 0;
                if (delta == 0.0f) {
                    if (upper ? from > limit : from < limit) return false;
                    continue;
                }
                const float s = (limit - from) / delta;
                if ((delta > 0) == upper) hi_s = std::min(hi_s, s);
                else lo_s = std::max(lo_s, s);
            }
        }
        if (!(lo_s < hi_s)) return false;
        const light_point a0 = a, b0 = b;
        const float ia = 1.0f / a0.w, ib = 1.0f / b0.w;
        auto weights = [&](float s) { return rounded(rounded((1.0f - s) * ia) + rounded(s * ib)); }; // (1 - s) / w_a + s / w_b
        auto perspective = [&](float s) { return rounded(s * ib) / weights(s); };                     // window -> attribute parameter
        auto end = [&](float s) {
            return light_point{glm::vec2(std::clamp(a0.window.x + rounded(s * (b0.window.x - a0.window.x)), -guard_band, guard_band),
                                         std::clamp(a0.window.y + rounded(s * (b0.window.y - a0.window.y)), -guard_band, guard_band)),
                               lerp_exact(a0.depth, b0.depth, perspective(s)), 1.0f / weights(s)};
        };
        const float u_lo = perspective(lo_s), u_hi = perspective(hi_s);
        at = {lerp_exact(at.thickness_a, at.thickness_b, u_lo), lerp_exact(at.thickness_a, at.thickness_b, u_hi),
              lerp_exact(at.opacity_a, at.opacity_b, u_lo), lerp_exact(at.opacity_a, at.opacity_b, u_hi)};
        a = end(lo_s), b = end(hi_s);
    }
    // Only finite ends inside the guard band reach the fixed-point rule (NaN fails every comparison).
    if (!(std::abs(a.window.x) <= guard_band && std::abs(a.window.y) <= guard_band && std::abs(b.window.x) <= guard_band &&
          std::abs(b.window.y) <= guard_band && std::abs(a.depth) <= 2.0f && std::abs(b.depth) <= 2.0f && a.w > 0.0f && b.w > 0.0f))
        return false;
    out = {{snap(a.window.x), snap(a.window.y), snap(b.window.x), snap(b.window.y), a.depth, b.depth}, 1.0f / a.w, 1.0f / b.w};
    return !out.empty();
}

/// The fragments of one segment: the parameter of a texel centre along it, and a fragment's depth and
/// alpha there. Every value is a function of the segment and the texel alone, so the tile a fragment
/// is made in cannot change it. A fragment's alpha is the strand's opacity times the share of the
/// texel its thickness covers (thickness / texel footprint, at most 1), or the fixed alpha; either is
/// clamped to HAIRSHADOW_ALPHA_MAX.
class segment_shader {
public:
    segment_shader(const light_space& light, const raster_options& options, const prepared_segment& s, const segment_attributes& at) noexcept
        : light_(&light), s_(s), at_(at), fixed_alpha_(options.fixed_alpha.value_or(-1.0f)),
          dx_(float(std::int64_t(s.bx) - s.ax)), dy_(float(std::int64_t(s.by) - s.ay)), inv_length2_(1.0f / rounded(rounded(dx_ * dx_) + rounded(dy_ * dy_))),
          perspective_(s.inv_w_a != s.inv_w_b),
          depth_varies_(light.perspective() && options.depth_weighting), footprint_(light.texel_size(0.5f)) {}

    /// Window-space parameter of the texel centre (x, y) along a -> b, clamped to [0, 1], as in GL's
    /// line interpolation: (p . d) / |d|^2 in float alone, every product rounded on its own (no fused
    /// multiply-add) and the reciprocal of |d|^2 taken once per segment, so that the AVX-512 walk and
    /// the GPU's compute build (shaders/compute/common.glsl, hs_parameter) make the same bits. The
    /// offsets and differences are exact integers; they and their products round once each where they
    /// pass 2^24, a few ULP of t on long segments.
    /// Negative values and -0 clamp to +0.
    HAIRSHADOW_ALWAYS_INLINE float parameter(int x, int y) const noexcept {
        constexpr std::int64_t S = subpixel_scale, H = S / 2;
        const float px = float(std::int64_t(x) * S + H - s_.ax), py = float(std::int64_t(y) * S + H - s_.ay);
        const float t = rounded(rounded(px * dx_) + rounded(py * dy_)) * inv_length2_;
        return t > 0.0f ? std::min(t, 1.0f) : 0.0f;
    }

    /// The fragment's linear depth at window parameter t (the depth of shade(t)).
    HAIRSHADOW_ALWAYS_INLINE float depth(float t) const noexcept { return lerp_exact(s_.depth_a, s_.depth_b, attribute_parameter(t)); }

    /// The fragment at window parameter t, its alpha scaled by `weight` (wide lines' profile).
    HAIRSHADOW_ALWAYS_INLINE fragment shade(float t, float weight = 1.0f) const noexcept {
        const float s = attribute_parameter(t);
        const float depth = lerp_exact(s_.depth_a, s_.depth_b, s);
        float alpha;
        if (fixed_alpha_ >= 0.0f) {
            alpha = fixed_alpha_ * weight;
        } else {
            const float thickness = lerp_exact(at_.thickness_a, at_.thickness_b, s);
            const float opacity = lerp_exact(at_.opacity_a, at_.opacity_b, s);
            const float footprint = depth_varies_ ? light_->texel_size(depth) : footprint_;
            alpha = opacity * std::min(1.0f, thickness / footprint) * weight;
        }
        return {depth, alpha > 0.0f ? std::min(alpha, HAIRSHADOW_ALPHA_MAX) : 0.0f}; // NaN gives 0
    }

    /// Every fragment of the thin line has the alpha of shade(0): a fixed alpha, or constant thickness
    /// and opacity with a footprint that does not change with depth. (lerp_exact keeps equal ends
    /// exactly equal, so this is exact, not approximate.)
    bool constant_alpha() const noexcept {
        return fixed_alpha_ >= 0.0f || (!depth_varies_ && at_.thickness_a == at_.thickness_b && at_.opacity_a == at_.opacity_b);
    }

    const prepared_segment& segment() const noexcept { return s_; }
    /// 1/w changes along the segment: attributes are interpolated perspective-correctly.
    bool perspective() const noexcept { return perspective_; }

private:
    /// Perspective-correct parameter of the attributes at window parameter t: t itself unless 1/w
    /// changes along the segment.
    HAIRSHADOW_ALWAYS_INLINE float attribute_parameter(float t) const noexcept {
        if (!perspective_) return t;
        const float wa = (1.0f - t) * s_.inv_w_a, wb = t * s_.inv_w_b;
        return wb / (wa + wb);
    }

    const light_space* light_;
    prepared_segment s_;
    segment_attributes at_;
    float fixed_alpha_;
    float dx_, dy_;        // b - a in sub-pixels
    float inv_length2_;    // 1 / |b - a|^2, correctly rounded
    bool perspective_, depth_varies_;
    float footprint_;
};

/// Pre-filtered wide line: texel centres within half the width of the segment's axis, between its
/// ends, weighted by a Gaussian (sigma = width / 4) truncated at the band's edge and normalised so
/// that it integrates to one texel across the band. Calls emit(x, y, t, weight).
template <class Emit>
void rasterize_wide_line(const prepared_segment& s, float width, const texel_rect& clip, Emit&& emit) {
    const double ax = double(s.ax) / subpixel_scale, ay = double(s.ay) / subpixel_scale;
    const double dx = double(std::int64_t(s.bx) - s.ax) / subpixel_scale, dy = double(std::int64_t(s.by) - s.ay) / subpixel_scale;
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

} // namespace hairshadow::detail
