#pragma once
/// @file
/// Reconstruction by a Fourier series: Fourier opacity maps (Jansen & Bavoil 2010). The absorption
/// along a texel's ray, a sum of spikes b_i at depths t_i in a period [0, 1], is projected on C
/// coefficients, a_0 = 2 sum b_i and a_k = 2 sum b_i cos(2 pi k t_i), b_k = 2 sum b_i sin(2 pi k t_i)
/// for k = 1 .. (C - 1) / 2; the optical depth in front of t is the integral of the truncated series,
///   tau(t) = a_0 t / 2 + sum_k [a_k sin(2 pi k t) + b_k (1 - cos(2 pi k t))] / (2 pi k),
/// exact at t = 1 (the texel's total) and ringing between spikes, since a truncated series of a spike
/// overshoots on both sides (Gibbs). The ringing's usual damping multiplies harmonic k by Lanczos'
/// sigma factor sinc(k / (n + 1)) (n harmonics): smoother, and blurrier. The harmonics come from
/// cos and sin of 2 pi t by the angle-sum recurrence, as open implementations do.
///
/// Where the period lies (our choice; the paper normalises depth between the light's near and far
/// planes): the texel's depth range (reconstruction/detail/depth_projection.hpp) maps onto
/// [m, 1 - m]. The series is periodic, so a spike at 1 is one at 0: with the range on the whole
/// period the nearest and furthest fragments would shadow each other. A spike's truncated series
/// (a Dirichlet kernel) has its main lobe within 1/C on each side; the sigma factors smooth it by a
/// box 1/(n + 1) = 2/(C + 1) wide, to 1/C + 1/(C + 1). m is that lobe, so the first and last
/// fragments' lobes never wrap around. docs/methods.md measures the ringing.

#include <hairshadow/core/error.hpp>
#include <hairshadow/reconstruction/detail/depth_projection.hpp>

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

namespace hairshadow {

/// Optical depth from C Fourier coefficients of each texel's absorption.
/// @tparam C coefficients: a_0 and (C - 1) / 2 pairs of a_k and b_k; odd, 3 to 15
template <int C>
class fourier_series : public detail::depth_projection<fourier_series<C>, C> {
    static_assert(C >= 3 && C <= 15 && C % 2 == 1, "fourier_series needs an odd number of coefficients from 3 to 15");

public:
    static constexpr int coefficients = C;
    static constexpr int harmonics = (C - 1) / 2;
    /// a_0 = 2 b: what an 8-bit accumulation's encoding divides by (detail/depth_projection.hpp).
    static constexpr float terms_per_optical_depth = 2.0f;
    static constexpr std::string_view name = "fourier_series";
    static constexpr std::string_view glsl_name = "reconstruction/fourier_series";

    /// Undamped (the paper's series), or each harmonic damped by Lanczos' sigma factor.
    explicit fourier_series(bool damped = false)
        : damped_(damped), margin_(float(1.0 / C + (damped ? 1.0 / (C + 1) : 0.0))), span_(1.0f - 2.0f * margin_) {
        for (int k = 1; k <= harmonics; ++k) {
            // sinc(k / (n + 1)), in double and rounded once, so that CPU and GL take the same floats.
            const double x = std::numbers::pi * double(k) / double(harmonics + 1);
            const double sigma = damped ? std::sin(x) / x : 1.0;
            weight_[std::size_t(k)] = float(sigma / (2.0 * std::numbers::pi * double(k)));
        }
    }
    bool damped() const noexcept { return damped_; }
    /// Where the texel's range starts in the period (its main lobe: 1/C, damped 1/C + 1/(C + 1)).
    float margin() const noexcept { return margin_; }

    /// Adds a spike of optical depth b at position s of the texel's range to the coefficients.
    void project(float s, float b, double* terms) const noexcept {
        const float angle = 2.0f * std::numbers::pi_v<float> * (margin_ + span_ * s);
        const float c1 = std::cos(angle), s1 = std::sin(angle);
        const float a0 = 2.0f * b;
        terms[0] += double(a0);
        float ck = c1, sk = s1;
        for (int k = 1; k <= harmonics; ++k) {
            terms[2 * k - 1] += double(a0 * ck);
            terms[2 * k] += double(a0 * sk);
            const float c = ck * c1 - sk * s1, s2 = sk * c1 + ck * s1;
            ck = c, sk = s2;
        }
    }
    /// The texel's total optical depth: a_0 / 2.
    static float total_optical_depth(const float* stored) noexcept { return 0.5f * stored[0]; }
    /// The integral of the (damped) truncated series from 0 to position s of the texel's range.
    float series_optical_depth(const float* stored, float s) const noexcept {
        const float t = margin_ + span_ * s;
        const float angle = 2.0f * std::numbers::pi_v<float> * t;
        const float c1 = std::cos(angle), s1 = std::sin(angle);
        float tau = 0.5f * stored[0] * t;
        float ck = c1, sk = s1;
        for (int k = 1; k <= harmonics; ++k) {
            tau += weight_[std::size_t(k)] * (stored[2 * k - 1] * sk + stored[2 * k] * (1.0f - ck));
            const float c = ck * c1 - sk * s1, s2 = sk * c1 + ck * s1;
            ck = c, sk = s2;
        }
        return tau;
    }

    /// The GLSL twin (shaders/reconstruction/fourier_series.glsl): the harmonics, and each one's
    /// weight (sigma factor over 2 pi k) as the CPU rounded it.
    static std::string glsl_defines() { return "#define HS_HARMONICS " + std::to_string(harmonics) + "\n"; }
    template <class Set>
    void glsl_uniforms(Set&& set) const {
        set("hs_fourier_margin", margin_);
        set("hs_fourier_span", span_);
        for (int k = 1; k <= harmonics; ++k) set("hs_fourier_weight", weight_[std::size_t(k)], k); // element k of the array
    }

private:
    bool damped_ = false;
    float margin_, span_;
    std::array<float, std::size_t(harmonics + 1)> weight_{};
};

} // namespace hairshadow
