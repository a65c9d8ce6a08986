#pragma once
/// @file
/// The real roots of c_0 + c_1 z + .. + c_n z^n (n = 2, 3, 4) whose roots are all real, as the
/// canonical distributions of power moments give them (reconstruction/power_moments.hpp).
///
/// Degree 2 by the quadratic formula as moment shadow maps have always solved it (kept bit for bit).
/// Degrees 3 and 4 by isolation and bisection rather than Viete's or Ferrari's closed forms: a
/// canonical distribution often has a point far out (c_n small beside the others), and there the
/// closed forms, which shift by c_(n-1) / c_n, lose the roots near [-1, 1] to cancellation (the moment
/// bound, measured on random texels, then failed by up to 68 times the texel's total). The roots of a
/// polynomial whose roots are all real are separated by those of its derivative (Rolle), so each
/// interval between the derivative's roots (found the same way, down to a quadratic solved in the
/// stable form) holds one root, where the polynomial is monotonic; the outer ones are bracketed by
/// doubling a step outward. A fixed number of halvings then narrows each bracket to the float
/// resolution. Only float additions, multiplications, divisions and comparisons, in one order that
/// shaders/reconstruction/power_moments.glsl repeats.

#include <algorithm>
#include <array>
#include <cmath>

namespace hairshadow::detail {

/// Halvings of a root's bracket: from a bracket of width 2^k, about k + 24 halvings reach float
/// resolution near 1, so 40 bring an inner bracket (at most a few units wide) to it; an outer one may
/// be up to 2^60 wide, and 40 halvings still leave its root to within 2^-40 of the bracket, fine for
/// a root that far out, whose relative precision is what the weights need.
inline constexpr int root_bisection_steps = 40;
/// Doublings of the step outward that brackets the outermost roots (2^60 at most).
inline constexpr int root_bracket_doublings = 60;

/// c[0] + c[1] z + .. + c[n] z^n, by Horner's rule.
template <int n>
float polynomial_at(const float* c, float z) noexcept {
    float value = c[n];
    for (int k = n - 1; k >= 0; --k) value = value * z + c[k];
    return value;
}

/// The root of the n-degree polynomial c in [lo, hi], where it changes sign once. Where rounding
/// leaves the same sign at both ends (a double root at a critical point), the end nearer zero.
template <int n>
float bisected_root(const float* c, float lo, float hi) noexcept {
    const float at_lo = polynomial_at<n>(c, lo), at_hi = polynomial_at<n>(c, hi);
    const bool negative_at_lo = at_lo < 0.0f;
    if ((at_hi < 0.0f) == negative_at_lo) return std::abs(at_lo) <= std::abs(at_hi) ? lo : hi;
    for (int step = 0; step < root_bisection_steps; ++step) {
        const float mid = 0.5f * (lo + hi);
        const bool below = (polynomial_at<n>(c, mid) < 0.0f) == negative_at_lo; // the root lies above mid
        lo = below ? mid : lo; // selects, not branches: the side is a coin toss
        hi = below ? hi : mid;
    }
    return 0.5f * (lo + hi);
}

/// The roots of c[0] + c[1] z + .. + c[n] z^n, all real, in ascending order for n >= 3.
template <int n>
std::array<float, std::size_t(n)> real_roots(const float* c) noexcept {
    static_assert(n >= 2 && n <= 4, "real_roots solves degrees 2 to 4");
    if constexpr (n == 2) {
        const float p = c[1] / c[2], q = c[0] / c[2];
        const float r = std::sqrt(0.25f * p * p - q);
        return {-0.5f * p - r, -0.5f * p + r};
    } else {
        // The derivative's roots, ascending.
        float slope[n];
        for (int k = 0; k < n; ++k) slope[k] = float(k + 1) * c[k + 1];
        std::array<float, std::size_t(n - 1)> critical{};
        if constexpr (n == 3) {
            // The stable form of the quadratic formula: no cancellation where slope[2] is small.
            const float middle = 0.5f * slope[1];
            const float root = std::sqrt(std::max(middle * middle - slope[0] * slope[2], 0.0f));
            const float t = -(middle + (middle < 0.0f ? -root : root));
            const float z1 = t / slope[2], z2 = slope[0] / t;
            critical = {std::min(z1, z2), std::max(z1, z2)};
        } else {
            critical = real_roots<n - 1>(slope);
        }
        std::array<float, std::size_t(n)> roots{};
        for (int i = 0; i < n; ++i) {
            float lo, hi;
            if (i == 0 || i == n - 1) {
                // Outward from the outermost critical point until the sign changes.
                const float from = i == 0 ? critical[0] : critical[std::size_t(n - 2)], direction = i == 0 ? -1.0f : 1.0f;
                const bool negative_at_from = polynomial_at<n>(c, from) < 0.0f;
                float step = 1.0f, to = from + direction * step;
                for (int k = 0; k < root_bracket_doublings && (polynomial_at<n>(c, to) < 0.0f) == negative_at_from; ++k) {
                    step = 2.0f * step;
                    to = from + direction * step;
                }
                if ((polynomial_at<n>(c, to) < 0.0f) == negative_at_from) {
                    roots[std::size_t(i)] = from; // no change of sign: rounding merged a double root at the critical point
                    continue;
                }
                lo = i == 0 ? to : from;
                hi = i == 0 ? from : to;
            } else {
                lo = critical[std::size_t(i - 1)];
                hi = critical[std::size_t(i)];
            }
            roots[std::size_t(i)] = bisected_root<n>(c, lo, hi);
        }
        return roots;
    }
}

} // namespace hairshadow::detail
