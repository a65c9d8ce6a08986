#pragma once
/// @file
/// Deep samples from shadow maps (io/deep_exr.hpp): the exact map's fragments as point samples, a
/// compressed map's piecewise-linear functions as point and volume samples, and the compositing of
/// OpenEXR's "Interpreting OpenEXR Deep Pixels" for the alpha channel alone. Needs no OpenEXR.

#include <hairshadow/core/light.hpp>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <span>
#include <vector>

namespace hairshadow {

/// One deep sample: a point sample where z_back == z, else a volume sample over [z, z_back] whose
/// alpha builds up inside it as for a uniform extinction (OpenEXR's rule: 1 - (1 - alpha)^fraction).
struct deep_sample {
    float z;
    float z_back;
    float alpha;
};

/// What write_deep_exr needs of the exact map (reference/deep_shadow_map.hpp): io/ ranks below
/// reference/, so the writer takes any type of that shape.
template <class Map>
concept exact_deep_map = requires(const Map& m) {
    { m.light() } -> std::convertible_to<const light_space&>;
    { m.depths(0, 0) } -> std::convertible_to<std::span<const float>>;
    { m.optical_depths(0, 0) } -> std::convertible_to<std::span<const float>>;
};

/// What write_deep_exr needs of a compressed map (reference/compressed_deep_shadow_map.hpp).
template <class Map>
concept compressed_deep_map = requires(const Map& m) {
    { m.light() } -> std::convertible_to<const light_space&>;
    { m.tolerance() } -> std::convertible_to<float>;
    { m.vertices(0, 0)[0].depth } -> std::convertible_to<float>;
    { m.vertices(0, 0)[0].transmittance } -> std::convertible_to<float>;
};

namespace detail {

/// Optical depth -ln(1 - alpha) of a whole sample (infinite where alpha is 1).
inline double sample_optical_depth(const deep_sample& s) noexcept { return -std::log1p(-double(s.alpha)); }

/// The part of sample `s` in front of `depth`, as optical depth: a point sample counts whole when it
/// lies strictly in front (the exact map's rule), a volume sample by the fraction of it in front.
inline double optical_depth_in_front(const deep_sample& s, float depth) noexcept {
    if (!(s.z < depth)) return 0.0;
    if (!(s.z_back > depth)) return sample_optical_depth(s);
    const double fraction = (double(depth) - double(s.z)) / (double(s.z_back) - double(s.z));
    return s.alpha >= 1.0f ? sample_optical_depth(s) : fraction * sample_optical_depth(s);
}

/// One texel of the exact map as point samples, front to back: alpha = 1 - exp(-(omega_i - omega_{i-1}))
/// from the cumulative optical depths, in double. Fragments at one depth become one sample (their
/// alphas combined), so that no two point samples coincide and the image is tidy; the exact map
/// counts such fragments together anyway (strictly in front or not).
inline void exact_texel_samples(std::span<const float> depths, std::span<const float> optical_depths, std::vector<deep_sample>& out) {
    double before = 0.0;
    for (std::size_t i = 0; i < depths.size(); ++i) {
        if (i + 1 < depths.size() && depths[i + 1] == depths[i]) continue;
        const double omega = optical_depths[i];
        out.push_back({depths[i], depths[i], float(-std::expm1(-(omega - before)))});
        before = omega;
    }
}

/// The largest gap, inside one volume sample, between the linear function from p to q and OpenEXR's
/// exponential one p (q/p)^f (f the fraction of the sample in front). Both are monotone between p and
/// q, so the gap is at most |p - q|. For p, q > 0, g(f) = p (q/p)^f is convex with
/// g''(f) = g(f) ln^2(q/p) <= max(p, q) ln^2(q/p), and the chord of a convex function lies at most
/// max|g''| / 8 above it over a unit interval (the error bound of linear interpolation), so the gap is
/// at most max(p, q) ln^2(q/p) / 8.
inline double volume_gap_bound(double p, double q) noexcept {
    const double hi = std::max(p, q), lo = std::min(p, q);
    if (!(lo > 0.0)) return hi - lo;
    const double l = std::log(hi / lo);
    return std::min(hi - lo, hi * l * l / 8.0);
}

/// The least budget a volume sample is held to: values 2^-24 apart are one float's rounding apart,
/// so a tolerance below 16 x 2^-24 is held to 2^-24 (volume_cuts then needs at most about 2900 pieces a sloped piece).
inline constexpr double least_volume_budget = 0x1p-24;

/// Where a linear piece falling from a to b (a > b >= 0) is cut so that every sub-piece is within
/// `budget` of its volume sample (volume_gap_bound), as the values after a, ending with b. Greedy
/// from the front: a sub-piece from p runs to q = p exp(-sqrt(8 budget / p)), where
/// p ln^2(p / q) / 8 = budget (a thousandth shorter, for rounding), or to b once p - b <= budget or
/// q <= b. Cut so, geometrically in T, a piece needs about sqrt(a / (2 budget)) sub-pieces (22 from
/// 0.5 down to 0 at tolerance 0.01, where equal cuts need |a - b| / budget = 800: near T = 0 the
/// exponential bends hardest).
/// Transmittances lie in [0, 1], so at most about 2900 cuts are made; the loop stops at 4096 in any
/// case (an input outside [0, 1] then gets a last piece to b, outside the bound).
inline void volume_cuts(double a, double b, double budget, std::vector<double>& cuts) {
    cuts.clear();
    budget = std::max(budget, least_volume_budget);
    double p = a;
    for (int n = 0; n < 4096; ++n) {
        const double q = p * std::exp(-std::sqrt(8.0 * 0.999 * budget / p));
        if (!(p - b > budget) || !(q > b)) break; // NaN ends it too
        cuts.push_back(q);
        p = q;
    }
    cuts.push_back(b);
}

/// A vertex of a texel's falling envelope (falling_envelope).
struct envelope_vertex {
    float depth;
    double transmittance;
};

/// The running minimum of a compressed function clamped at 0, as vertices of the same form (equal
/// depths a vertical step, 1 before the first). A compressed function may rise a little where its
/// greedy segments overshoot, but a sample's alpha must lie in [0, 1] (OpenEXR's "Interpreting
/// OpenEXR Deep Pixels"), so a composite can only fall. The exact function never rises, so wherever
/// the compressed one is within the tolerance of it, so is this envelope: min over z' <= z of c(z')
/// is at most c(z) <= T(z) + eps and at least min T(z') - eps = T(z) - eps.
template <class Vertices>
void falling_envelope(const Vertices& v, std::vector<envelope_vertex>& out) {
    out.clear();
    double least = 1.0; // the running minimum so far
    for (std::size_t i = 0; i < v.size(); ++i) {
        float z = v[i].depth;
        const double raw = double(v[i].transmittance);
        if (out.empty()) out.push_back({z, least}); // the value before the first vertex: 1
        if (!(std::max(raw, 0.0) < least)) continue; // at or above the running minimum: the envelope stays flat
        float start = z;                              // where the envelope leaves `least`
        if (i > 0 && v[i - 1].depth < z) {            // a sloped piece from the last vertex, linear in the raw values
            const float z0 = v[i - 1].depth;
            const double before = double(v[i - 1].transmittance);
            const auto depth_where = [&](double value) { // where the piece takes `value`, between its ends
                return std::clamp(float(double(z0) + (double(z) - double(z0)) * (before - value) / (before - raw)), z0, z);
            };
            start = before > least ? depth_where(least) : z0;
            if (raw < 0.0) z = depth_where(0.0); // clamped at 0 from where the piece crosses it, not from its end
        }
        if (out.back().depth < start) out.push_back({start, least});
        out.push_back({z, std::max(raw, 0.0)});
        least = std::max(raw, 0.0);
    }
}

/// Builds the samples of one texel's falling envelope: `level` is the transmittance the samples so
/// far composite to (with their float alphas), so that rounding does not drift; each sample's alpha,
/// in [0, 1), takes it to the envelope's next value (never up: a target above the level, by
/// rounding, gives no sample). An alpha stops at the float below 1, so that the level never becomes 0.
class compressed_texel_writer {
public:
    compressed_texel_writer(std::vector<deep_sample>& out, double budget) : out_(out), budget_(budget) {}

    void step(float z, double target) { emit(z, z, target); }

    /// The linear piece from (z0, a) to (z1, b), z0 < z1, a >= b >= 0, as volume samples within the
    /// budget. The cuts' depths are rounded to float and each target taken on the line at the rounded
    /// depth; where a piece spans only a few floats, a sub-piece so lengthened (or merged with the
    /// next) can pass the budget by the rounding.
    void slope(float z0, double a, float z1, double b) {
        if (a == b) return;
        volume_cuts(a, b, budget_, cuts_);
        float front = z0;
        for (std::size_t k = 0; k < cuts_.size(); ++k) {
            const float back = k + 1 == cuts_.size() ? z1 : float(double(z0) + (double(z1) - double(z0)) * (a - cuts_[k]) / (a - b));
            if (!(back > front)) continue; // fewer float depths than pieces: each piece is then one float step
            emit(front, back, a + (b - a) * (double(back) - double(z0)) / (double(z1) - double(z0)));
            front = back;
        }
    }

private:
    void emit(float z, float z_back, double target) {
        if (!(target < level_)) return;
        const float alpha = std::min(float(1.0 - target / level_), std::nextafter(1.0f, 0.0f));
        if (!(alpha > 0.0f)) return;
        out_.push_back({z, z_back, alpha});
        level_ *= 1.0 - double(alpha);
    }
    std::vector<deep_sample>& out_;
    double budget_;
    double level_ = 1.0;
    std::vector<double> cuts_;
};

/// One texel of a compressed map (vertices: depth, transmittance; equal depths a vertical step; 1 up
/// to the first vertex, continuous from the left at steps) as samples of its falling envelope: each
/// step a point sample at its depth, each sloped piece volume samples within `budget` of it.
template <class Vertices>
void compressed_texel_samples(const Vertices& vertices, double budget, std::vector<deep_sample>& out) {
    std::vector<envelope_vertex> v;
    falling_envelope(vertices, v);
    compressed_texel_writer writer(out, budget);
    for (std::size_t i = 0; i < v.size();) {
        std::size_t j = i;
        while (j + 1 < v.size() && v[j + 1].depth == v[i].depth) ++j;
        const double left = v[i].transmittance;
        if (v[j].transmittance != left) writer.step(v[i].depth, v[j].transmittance);
        if (j + 1 < v.size()) writer.slope(v[j].depth, v[j].transmittance, v[j + 1].depth, v[j + 1].transmittance);
        i = j + 1;
    }
}

} // namespace detail
} // namespace hairshadow
