#pragma once
/// @file
/// What Fourier opacity maps and moment shadow maps share: each texel keeps N sums of its fragments'
/// optical depth b times N functions of the fragment's depth (a Fourier basis, powers of depth), and
/// the look-up turns the sums into the optical depth in front of a depth. Depths are measured inside
/// the texel's own depth range (depth_range's nearest and furthest fragment: s = 0 at the nearest,
/// 1 at the furthest), so that every texel spends its functions where its hair is; the papers use one
/// interval for the whole map, which is the special case of one range for every texel.
///
/// A Derived reconstruction provides `void project(float s, float b, double* terms) const` (adds b
/// times its N functions at s), `float total_optical_depth(const float* stored) const` and `float
/// series_optical_depth(const float* stored, float s) const` (the optical depth in front of s, for
/// 0 <= s <= 1), and their GLSL twins (gl/maps/projected_maps.hpp). Sums are kept in double and
/// stored once as float, close to the GL compute build's exact fixed-point sums (tests/gl compare
/// them within 1e-5 of the texel's largest sum).
///
/// An accumulation that stores quantised steps (emulated_8bit: additive blending into RGBA8 targets)
/// adds only non-negative values, so the signed terms t_k are stored as steps of b (1 + t_k / t_0) / 2,
/// between 0 and b where |t_k| <= t_0 (a Fourier term beside a_0, a power of z in [-1, 1] beside 1),
/// and term 0 as b itself: t_0 = c b for Derived's `terms_per_optical_depth` c (1 unless it says so),
/// a power of two, so that the steps are (t_0 + t_k) / (2 c) and t_0 / c, each one float rounding,
/// as in GLSL. The look-up decodes S_k, the sum of step k, back to the signed sums: t_0 = c B and
/// t_k = c (2 S_k - B) with B = S_0 (the texel's optical depth, saturated as the 8-bit accumulation
/// saturates it).

#include <hairshadow/reconstruction/fibre_density.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <type_traits>

namespace hairshadow {

/// A texel's projected sums: sums[0] is always the texel's total optical depth times a constant
/// (`Value`: float sums, or an 8-bit accumulation's steps of the encoded terms).
template <int N, class Value = float>
struct projected_sums {
    std::array<Value, std::size_t(N)> sums{};
    friend bool operator==(const projected_sums&, const projected_sums&) = default;
};

namespace detail {

/// Whether an accumulation stores quantised steps (emulated_8bit) rather than float sums.
template <class Accumulation>
inline constexpr bool quantised_accumulation = !std::is_floating_point_v<typename Accumulation::value_type>;

/// Term 0 over a fragment's optical depth: the reconstruction's `terms_per_optical_depth`, 1 where it
/// gives none; a power of two from 1 to 8, so that the 8-bit encoding's scalings are exact.
template <class Derived>
constexpr float terms_per_optical_depth() noexcept {
    constexpr float c = [] {
        if constexpr (requires { Derived::terms_per_optical_depth; }) return float(Derived::terms_per_optical_depth);
        else return 1.0f;
    }();
    static_assert(c == 1.0f || c == 2.0f || c == 4.0f || c == 8.0f, "terms_per_optical_depth must be 1, 2, 4 or 8");
    return c;
}

/// Where `depth` lies in the texel's range: 0 at the nearest fragment, 1 at the furthest (0 for
/// every depth where the range is one depth).
inline float position_in_range(float nearest, float furthest, float depth) noexcept {
    const float span = furthest - nearest;
    return span > 0.0f ? std::clamp((depth - nearest) / span, 0.0f, 1.0f) : 0.0f;
}

/// The reconstruction of a texel's optical depth from its projected sums (see the file's comment).
template <class Derived, int N>
class depth_projection {
public:
    static constexpr int sums = N;
    /// Needs the texel's nearest and furthest fragment (depth_range).
    template <class Placement>
    static constexpr bool accepts = fragment_span_state<Placement>;

    template <class Placement, class Accumulation>
    using storage = projected_sums<N, typename Accumulation::value_type>;

    template <class Placement, class Accumulation, class Fragment>
    void build(const Placement&, const typename Placement::texel_state& state, std::span<const Fragment> fragments,
               storage<Placement, Accumulation>& out) const {
        if constexpr (!quantised_accumulation<Accumulation>) {
            std::array<double, std::size_t(N)> terms{};
            for (const auto& f : fragments)
                derived().project(position_in_range(state.nearest, state.furthest, f.depth), fragment_optical_depth(f), terms.data());
            for (int k = 0; k < N; ++k) out.sums[std::size_t(k)] = float(terms[std::size_t(k)]);
        } else {
            std::array<typename Accumulation::sum_type, std::size_t(N)> steps{};
            for (const auto& f : fragments) {
                std::array<double, std::size_t(N)> terms{}; // one fragment's terms, each a float
                derived().project(position_in_range(state.nearest, state.furthest, f.depth), fragment_optical_depth(f), terms.data());
                const float t0 = float(terms[0]);
                constexpr float c = terms_per_optical_depth<Derived>();
                steps[0] = Accumulation::add(steps[0], t0 * (1.0f / c));
                for (int k = 1; k < N; ++k) {
                    const float step = (t0 + float(terms[std::size_t(k)])) * (0.5f / c);
                    steps[std::size_t(k)] = Accumulation::add(steps[std::size_t(k)], step);
                }
            }
            for (int k = 0; k < N; ++k) out.sums[std::size_t(k)] = Accumulation::store(steps[std::size_t(k)]);
        }
    }

    /// The signed sums a texel's storage stands for (see the file's comment).
    template <class Accumulation>
    static std::array<float, std::size_t(N)> decoded(const projected_sums<N, typename Accumulation::value_type>& in) noexcept {
        if constexpr (!quantised_accumulation<Accumulation>) {
            return in.sums;
        } else {
            std::array<float, std::size_t(N)> out{};
            const float total = Accumulation::decode(in.sums[0]);
            constexpr float c = terms_per_optical_depth<Derived>();
            out[0] = c * total;
            for (int k = 1; k < N; ++k) out[std::size_t(k)] = c * (2.0f * Accumulation::decode(in.sums[std::size_t(k)]) - total);
            return out;
        }
    }

    /// Nothing in front of the nearest fragment, the whole texel's optical depth behind the furthest
    /// (the exact map counts the fragments strictly in front), and between them the series, held
    /// within [0, total] (Derived's series may ring outside it).
    template <class Placement, class Accumulation>
    float optical_depth(const Placement&, const typename Placement::texel_state& state, const storage<Placement, Accumulation>& in,
                        float depth) const noexcept {
        const auto signed_sums = decoded<Accumulation>(in);
        const float total = derived().total_optical_depth(signed_sums.data());
        if (!(depth > state.nearest) || !(total > 0.0f)) return 0.0f;
        if (depth > state.furthest) return total;
        const float tau = derived().series_optical_depth(signed_sums.data(), position_in_range(state.nearest, state.furthest, depth));
        return tau > 0.0f ? std::min(tau, total) : 0.0f; // and a series that came to NaN (a singular moment matrix) casts none
    }

    /// The stored sums, for inspection.
    template <class Placement>
    static constexpr int stored_maps = N;
    template <class Placement, class Accumulation>
    static float stored_optical_depth(const storage<Placement, Accumulation>& in, int k) noexcept {
        return decoded<Accumulation>(in)[std::size_t(k)];
    }

private:
    const Derived& derived() const noexcept { return static_cast<const Derived&>(*this); }
};

} // namespace detail
} // namespace hairshadow
