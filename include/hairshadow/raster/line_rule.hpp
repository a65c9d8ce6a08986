#pragma once
/// @file
/// OpenGL's aliased line rule (the diamond-exit rule, GL 4.6 core section 14.5.1) in exact fixed-point
/// arithmetic of 32-bit integers (one 64-bit product and division per quotient of the set-up), the
/// same as the GPU's compute walk (shaders/compute/common.glsl, hs_walk). Fragment f is produced when
/// the segment meets f's diamond |x - xc| + |y - yc| < 1/2 and the segment's end is not inside it, with both endpoints moved by -(e, e^2) for a vanishing e, as the
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
static_assert(HAIRSHADOW_SUBPIXEL_BITS >= 1 && HAIRSHADOW_SUBPIXEL_BITS <= 9,
              "the line rule's 32-bit words hold guard-band coordinates at up to 9 sub-pixel bits");

/// o v / A as q + r / A with 0 <= r < A, exactly, for 0 <= o and |v| <= A (o is at most A, or S for the
/// step, so q fits 32 bits): the floor of the 64-bit product's quotient. (The GPU takes the same
/// quotient from 32-bit words, hs_product_quotient.)
struct quotient {
    std::int32_t q, r;
};
HAIRSHADOW_ALWAYS_INLINE inline quotient product_quotient(std::int32_t o, std::int32_t v, std::int32_t A) noexcept {
    const std::int64_t p = std::int64_t(o) * v;
    const std::int64_t q = floor_div(p, A);
    return {std::int32_t(q), std::int32_t(p - q * A)};
}

/// What both walks of the line rule work out for a segment a -> b and a clip rectangle: the major
/// axis, the texel centres on it that the segment crosses, those inside the clip, and the minor
/// coordinate at the first of them as k + r / A sub-pixels (A = |d_major|, 0 <= r < A) with its step
/// per texel, exactly, in 32-bit integers: every part stays within the guard band (2^20 texels of
/// 2^9 sub-pixels at most, so |k| < 2^30 and A <= 2^30, and r plus its step stays below 2^31), as on
/// the GPU (hs_walk).
struct line_walk {
    bool x_major;
    bool lower_on_tie;                     ///< ties on the minor axis go to the lower row or left column
    std::int32_t first, last;              ///< centres crossed on the major axis (texel indices)
    std::int32_t m_begin, m_end;           ///< the part of [first, last] inside the clip
    std::int32_t k, r, A;                  ///< the minor coordinate at m_begin: k + r / A sub-pixels
    std::int32_t step_k, step_r;           ///< its step per texel: step_k + step_r / A

    /// The minor texel at the current centre: the sub-pixel's texel, one lower on a tie (the
    /// coordinate exactly on a texel boundary).
    std::int32_t minor() const noexcept {
        const std::int32_t n = k >> HAIRSHADOW_SUBPIXEL_BITS; // an arithmetic shift floors
        return n - (std::int32_t(lower_on_tie) & std::int32_t(((k & std::int32_t(subpixel_scale - 1)) | r) == 0));
    }
    /// On to the next centre.
    void advance() noexcept {
        r += step_r;
        const std::int32_t carry = r >= A;
        r -= carry * A;
        k += step_k + carry;
    }
};

/// Sets up the walk of a -> b (not of zero length, within the guard band) in `clip`.
HAIRSHADOW_ALWAYS_INLINE inline line_walk set_up_line(const fixed_point& a, const fixed_point& b, const texel_rect& clip) noexcept {
    constexpr std::int32_t S = std::int32_t(subpixel_scale), H = S / 2, bits = HAIRSHADOW_SUBPIXEL_BITS;
    const auto ax = std::int32_t(a.x), ay = std::int32_t(a.y), bx = std::int32_t(b.x), by = std::int32_t(b.y);
    const std::int32_t dx = bx - ax, dy = by - ay;
    line_walk w{};
    w.x_major = std::abs(dx) >= std::abs(dy);
    const std::int32_t major_a = w.x_major ? ax : ay, major_b = w.x_major ? bx : by;
    const std::int32_t d_major = w.x_major ? dx : dy, d_minor = w.x_major ? dy : dx;
    const std::int32_t minor_a = w.x_major ? ay : ax;
    // Texel centres c*S + H on the major axis that the perturbed segment crosses: for increasing
    // coordinates major_a <= centre < major_b, for decreasing major_b <= centre < major_a. The
    // ceilings by the shift's floor.
    const std::int32_t lo_end = d_major > 0 ? major_a : major_b, hi_end = d_major > 0 ? major_b : major_a;
    w.first = (lo_end - H + S - 1) >> bits;
    w.last = ((hi_end - H + S - 1) >> bits) - 1;
    const std::int32_t clip_lo = w.x_major ? clip.x0 : clip.y0, clip_hi = w.x_major ? clip.x1 : clip.y1;
    w.m_begin = std::max(w.first, clip_lo);
    w.m_end = std::min(w.last, clip_hi - 1);
    w.A = std::abs(d_major);
    // Ties on the minor axis (the line through a texel corner row or column): an x-major line moves by
    // slope * e - e^2, so it goes to the lower row unless its slope is positive; a y-major line moves
    // by -e in x and always goes to the left column.
    w.lower_on_tie = !w.x_major || dy == 0 || (dx > 0) != (dy > 0);
    if (w.m_begin <= w.m_end) {
        // The first centre's distance from a along the major axis, o in [0, A] (first <= m_begin <=
        // last), puts the minor coordinate there at minor_a + o d_minor / A; each centre adds
        // S d_minor / A, |d_minor| <= A. Two divisions a call, none a texel.
        const std::int32_t sign = d_major > 0 ? 1 : -1;
        const quotient start = product_quotient(sign * (w.m_begin * S + H - major_a), d_minor, w.A);
        const quotient step = product_quotient(S, sign * d_minor, w.A);
        w.k = minor_a + start.q;
        w.r = start.r;
        w.step_k = step.q;
        w.step_r = step.r;
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
/// rasteriser's guard band), which keeps the walk's 32-bit words from overflowing.
template <class Emit>
HAIRSHADOW_ALWAYS_INLINE inline void rasterize_line(const fixed_point& a, const fixed_point& b, const texel_rect& clip, Emit&& emit) {
    if (a == b) return;
    detail::line_walk w = detail::set_up_line(a, b, clip);
    for (std::int32_t m = w.m_begin; m <= w.m_end; ++m, w.advance()) {
        const std::int32_t minor = w.minor();
        const std::int32_t x = w.x_major ? m : minor, y = w.x_major ? minor : m;
        if (clip.contains(x, y) && !detail::inside_diamond(b, x, y)) emit(int(x), int(y));
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
    detail::line_walk w = detail::set_up_line(a, b, clip);
    const std::int64_t minor_lo = w.x_major ? clip.y0 : clip.x0, minor_span = (w.x_major ? clip.y1 : clip.x1) - minor_lo;
    // The one texel whose diamond holds the end, if any (the open diamonds are disjoint, and the
    // boundary rule gives a shared point to one of them): it makes no fragment.
    std::int64_t end_major = std::numeric_limits<std::int64_t>::min(), end_minor = 0;
    for (const std::int64_t cx : {floor_div(b.x - 1, S), floor_div(b.x, S)})
        for (const std::int64_t cy : {floor_div(b.y - 1, S), floor_div(b.y, S)})
            if (detail::inside_diamond(b, cx, cy)) end_major = w.x_major ? cx : cy, end_minor = w.x_major ? cy : cx;
    for (std::int32_t m = w.m_begin; m <= w.m_end; ++m, w.advance()) {
        const std::int32_t minor = w.minor();
        const bool keep = std::uint64_t(minor - minor_lo) < std::uint64_t(minor_span) && !(m == end_major && minor == end_minor);
        emit(int(w.x_major ? m : minor), int(w.x_major ? minor : m), keep);
    }
    detail::start_fragment(a, b, clip, w, [&](int x, int y) HAIRSHADOW_ALWAYS_INLINE { emit(x, y, true); });
}

} // namespace hairshadow
