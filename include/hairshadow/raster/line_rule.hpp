#pragma once
/// @file
/// OpenGL's aliased line rule (the diamond-exit rule, GL 4.6 core section 14.5.1) in exact fixed-point
/// arithmetic. Fragment f is produced when the segment meets f's diamond |x - xc| + |y - yc| < 1/2 and
/// the segment's end is not inside it, with both endpoints moved by -(e, e^2) for a vanishing e, as the
/// specification perturbs them, so that boundary cases are decided the way it describes.

#include <hairshadow/config.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>

namespace hairshadow {

/// Window coordinates snapped to 1/subpixel_scale of a texel.
struct fixed_point {
    std::int64_t x, y;
    friend bool operator==(const fixed_point&, const fixed_point&) = default;
};

/// Sub-pixel steps per texel.
inline constexpr std::int64_t subpixel_scale = std::int64_t(1) << HAIRSHADOW_SUBPIXEL_BITS;

/// A half-open texel rectangle [x0, x1) x [y0, y1).
struct texel_rect {
    int x0, y0, x1, y1;
    bool contains(std::int64_t x, std::int64_t y) const noexcept { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

namespace detail {
inline std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept { // b > 0
    const std::int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}
inline std::int64_t ceil_div(std::int64_t a, std::int64_t b) noexcept { return -floor_div(-a, b); } // b > 0

/// Is point p, moved by -(e, e^2), inside the open diamond of texel (c, r)? On the boundary the
/// perturbation's x term decides: the point is inside exactly when it lies right of the centre.
inline bool inside_diamond(const fixed_point& p, std::int64_t c, std::int64_t r) noexcept {
    constexpr std::int64_t half = subpixel_scale / 2;
    const std::int64_t u = p.x - (c * subpixel_scale + half);
    const std::int64_t v = p.y - (r * subpixel_scale + half);
    const std::int64_t l1 = std::llabs(u) + std::llabs(v);
    return l1 < half || (l1 == half && u > 0);
}
} // namespace detail

namespace detail {
/// What both walks of the line rule work out for a segment a -> b and a clip rectangle: the major
/// axis, the texel centres on it that the segment crosses, those inside the clip, and the minor
/// coordinate at the first of them as an exact quotient and remainder with its step per texel.
struct line_walk {
    bool x_major;
    bool lower_on_tie;                     ///< ties on the minor axis go to the lower row or left column
    std::int64_t first, last;              ///< centres crossed on the major axis (texel indices)
    std::int64_t m_begin, m_end;           ///< the part of [first, last] inside the clip
    std::int64_t n, rem, denom;            ///< the minor coordinate at m_begin: n + rem / denom
    std::int64_t step_q, step_r;           ///< its step per texel: step_q + step_r / denom
};

/// Sets up the walk of a -> b (not of zero length) in `clip`.
HAIRSHADOW_ALWAYS_INLINE inline line_walk set_up_line(const fixed_point& a, const fixed_point& b, const texel_rect& clip) noexcept {
    constexpr std::int64_t S = subpixel_scale, H = subpixel_scale / 2;
    const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
    line_walk w{};
    w.x_major = std::llabs(dx) >= std::llabs(dy);
    const std::int64_t major_a = w.x_major ? a.x : a.y, major_b = w.x_major ? b.x : b.y;
    const std::int64_t d_major = w.x_major ? dx : dy, d_minor = w.x_major ? dy : dx;
    const std::int64_t minor_a = w.x_major ? a.y : a.x;
    // Texel centres c*S + H on the major axis that the perturbed segment crosses: for increasing
    // coordinates major_a <= centre < major_b, for decreasing major_b <= centre < major_a.
    const std::int64_t lo_end = d_major > 0 ? major_a : major_b, hi_end = d_major > 0 ? major_b : major_a;
    w.first = ceil_div(lo_end - H, S);
    w.last = ceil_div(hi_end - H, S) - 1;
    const std::int64_t clip_lo = w.x_major ? clip.x0 : clip.y0, clip_hi = w.x_major ? clip.x1 : clip.y1;
    w.m_begin = std::max(w.first, clip_lo);
    w.m_end = std::min(w.last, clip_hi - 1);
    w.denom = (d_major > 0 ? d_major : -d_major) * S;
    const std::int64_t sign = d_major > 0 ? 1 : -1;
    // Ties on the minor axis (the line through a texel corner row or column): an x-major line moves by
    // slope * e - e^2, so it goes to the lower row unless its slope is positive; a y-major line moves
    // by -e in x and always goes to the left column.
    w.lower_on_tie = !w.x_major || dy == 0 || (dx > 0) != (dy > 0);
    if (w.m_begin <= w.m_end) {
        // The minor coordinate at successive centres, num / denom, advances by a constant step: keep
        // its quotient and remainder exactly, with one division per call instead of one per texel.
        // |d_minor| <= |d_major| puts the step within [-denom, denom]: its quotient needs no division.
        const std::int64_t num0 = sign * (minor_a * d_major + (w.m_begin * S + H - major_a) * d_minor);
        w.n = floor_div(num0, w.denom);
        w.rem = num0 - w.n * w.denom;
        const std::int64_t step = sign * d_minor * S;
        w.step_q = step == w.denom ? 1 : (step < 0 ? -1 : 0);
        w.step_r = step - w.step_q * w.denom;
    }
    return w;
}

/// The start fragment: a segment that starts inside a diamond it does not cross the centre line of
/// still exits it. The perturbed start lies in the texel of (a.x - e, a.y - e^2). Calls emit(x, y)
/// when there is one inside the clip.
template <class Emit>
HAIRSHADOW_ALWAYS_INLINE inline void start_fragment(const fixed_point& a, const fixed_point& b, const texel_rect& clip, const line_walk& w, Emit&& emit) {
    const std::int64_t ax = floor_div(a.x - 1, subpixel_scale), ay = floor_div(a.y - 1, subpixel_scale);
    const std::int64_t a_major = w.x_major ? ax : ay;
    if (inside_diamond(a, ax, ay) && (a_major < w.first || a_major > w.last) && !inside_diamond(b, ax, ay) && clip.contains(ax, ay))
        emit(int(ax), int(ay));
}
} // namespace detail

/// Calls emit(x, y) for every fragment of the segment a -> b inside `clip`, following the diamond-exit
/// rule. A zero-length segment produces nothing. Coordinates must be within +-2^20 texels (the
/// rasteriser's guard band), which keeps every product below 2^63.
template <class Emit>
HAIRSHADOW_ALWAYS_INLINE inline void rasterize_line(const fixed_point& a, const fixed_point& b, const texel_rect& clip, Emit&& emit) {
    if (a == b) return;
    const detail::line_walk w = detail::set_up_line(a, b, clip);
    std::int64_t n = w.n, rem = w.rem;
    for (std::int64_t m = w.m_begin; m <= w.m_end; ++m) {
        const std::int64_t minor = (w.lower_on_tie && rem == 0) ? n - 1 : n;
        const std::int64_t x = w.x_major ? m : minor, y = w.x_major ? minor : m;
        if (clip.contains(x, y) && !detail::inside_diamond(b, x, y)) emit(int(x), int(y));
        n += w.step_q;
        rem += w.step_r;
        if (rem >= w.denom) rem -= w.denom, ++n;
    }
    detail::start_fragment(a, b, clip, w, emit);
}

/// The fragments of rasterize_line, in the same order, walked for speed: the tiled build calls it for
/// every segment of every tile. Each texel centre on the segment's major axis inside `clip` is passed
/// to emit(x, y, keep), with `keep` false where rasterize_line makes no fragment (the minor coordinate
/// outside the clip, or the end's own diamond), so that the caller can store every candidate and
/// advance by `keep`, with no branch to mispredict; then the start fragment, if there is one, with
/// keep true. No division runs per texel, and only one per call. Coordinates as for rasterize_line.
template <class Emit>
HAIRSHADOW_ALWAYS_INLINE inline void walk_line(const fixed_point& a, const fixed_point& b, const texel_rect& clip, Emit&& emit) {
    using detail::floor_div;
    constexpr std::int64_t S = subpixel_scale;
    if (a == b) return;
    const detail::line_walk w = detail::set_up_line(a, b, clip);
    const std::int64_t minor_lo = w.x_major ? clip.y0 : clip.x0, minor_span = (w.x_major ? clip.y1 : clip.x1) - minor_lo;
    const std::int64_t tie = w.lower_on_tie ? 1 : 0;
    // The one texel whose diamond holds the end, if any (the open diamonds are disjoint, and the
    // boundary rule gives a shared point to one of them): it makes no fragment.
    std::int64_t end_major = std::numeric_limits<std::int64_t>::min(), end_minor = 0;
    for (const std::int64_t cx : {floor_div(b.x - 1, S), floor_div(b.x, S)})
        for (const std::int64_t cy : {floor_div(b.y - 1, S), floor_div(b.y, S)})
            if (detail::inside_diamond(b, cx, cy)) end_major = w.x_major ? cx : cy, end_minor = w.x_major ? cy : cx;
    std::int64_t n = w.n, rem = w.rem;
    for (std::int64_t m = w.m_begin; m <= w.m_end; ++m) {
        const std::int64_t minor = n - (tie & std::int64_t(rem == 0));
        const bool keep = std::uint64_t(minor - minor_lo) < std::uint64_t(minor_span) && !(m == end_major && minor == end_minor);
        emit(int(w.x_major ? m : minor), int(w.x_major ? minor : m), keep);
        rem += w.step_r;
        const std::int64_t carry = rem >= w.denom;
        rem -= carry * w.denom;
        n += w.step_q + carry;
    }
    detail::start_fragment(a, b, clip, w, [&](int x, int y) HAIRSHADOW_ALWAYS_INLINE { emit(x, y, true); });
}

} // namespace hairshadow
