#pragma once
/// @file
/// Reconstruction by power moments: moment shadow maps for translucent occluders (Peters et al. 2016)
/// as moment-based order-independent transparency computes them (Münstermann et al. 2018). Each
/// texel keeps its total optical depth b_0 = sum b_i and the optical-depth-weighted power moments
/// sum b_i z_i^j, j = 1 .. 4, of depth z in [-1, 1] (here the texel's depth range: -1 at its nearest
/// fragment, 1 at its furthest; reconstruction/detail/depth_projection.hpp). A query at z normalises
/// the moments by b_0, pulls them toward a fixed vector by a small bias (a singular Hankel matrix
/// otherwise: two sheets of hair are two depths), and solves for the canonical distribution with one
/// support point at z (Hamburger 4MSM): the weight of its points in front of z, plus `overestimation`
/// times the weight at z, is the share of b_0 in front. Overestimation 0 gives the sharpest lower bound
/// of that share over every distribution with these moments (a bound on the exact optical depth from
/// below, which the bias loosens a little), 1 the upper bound; MBOIT's 0.25 is the default.
/// docs/methods.md checks the bound on the test models.

#include <hairshadow/core/error.hpp>
#include <hairshadow/reconstruction/detail/depth_projection.hpp>

#include <cmath>
#include <string>
#include <string_view>

namespace hairshadow {

/// What the moment reconstruction takes.
struct power_moments_parameters {
    /// The weight the canonical distribution's point at the query depth counts with: 0 the lower
    /// bound, 1 the upper, MBOIT's 0.25 by default.
    float overestimation = 0.25f;
    /// How far the normalised moments are pulled toward (0, 0.375, 0, 0.375): MBOIT's bias vector for 4
    /// power moments in 32-bit floats, with a bias of 5e-7 (our choice; at it the bound holds within
    /// 1e-3 of a texel's total on Sintel and on sheets of strands, tests/test_moment_shadow_maps.cpp).
    float bias = 5e-7f;
    /// Throws argument_error unless the overestimation is in [0, 1] and the bias in [1e-7, 1]: with
    /// less, a texel of two depths (its range's ends, z = -1 and 1) leaves the Hankel matrix singular.
    void check() const {
        if (!(overestimation >= 0.0f && overestimation <= 1.0f)) throw argument_error("power moments: the overestimation must be in [0, 1]");
        if (!(bias >= 1e-7f && bias <= 1.0f)) throw argument_error("power moments: the bias must be in [1e-7, 1]");
    }
    friend bool operator==(const power_moments_parameters&, const power_moments_parameters&) = default;
};

/// Optical depth from the total and four power moments of each texel's absorption.
class power_moments : public detail::depth_projection<power_moments, 5> {
public:
    static constexpr int moments = 4;
    static constexpr std::string_view name = "power_moments";
    static constexpr std::string_view glsl_name = "reconstruction/power_moments";

    power_moments() = default;
    explicit power_moments(const power_moments_parameters& parameters) : parameters_(parameters) { parameters.check(); }
    const power_moments_parameters& parameters() const noexcept { return parameters_; }

    /// Adds b and b z, b z^2, b z^3, b z^4 at z = 2 s - 1.
    static void project(float s, float b, double* terms) noexcept {
        const float z = 2.0f * s - 1.0f;
        float power = b;
        terms[0] += double(b);
        for (int j = 1; j <= moments; ++j) {
            power = power * z;
            terms[j] += double(power);
        }
    }
    static float total_optical_depth(const float* stored) noexcept { return stored[0]; }

    /// b_0 times the share of it in front of position s (Hamburger 4MSM, in float as the GLSL twin).
    float series_optical_depth(const float* stored, float s) const noexcept {
        const float b0 = stored[0], keep = 1.0f - parameters_.bias, pull = parameters_.bias * 0.375f;
        const float b1 = keep * (stored[1] / b0), b2 = keep * (stored[2] / b0) + pull;
        const float b3 = keep * (stored[3] / b0), b4 = keep * (stored[4] / b0) + pull;
        const float z0 = 2.0f * s - 1.0f;
        // Cholesky factorisation of the Hankel matrix of (1, b1, b2, b3, b4).
        const float d11 = b2 - b1 * b1;
        const float l21d11 = b3 - b1 * b2;
        const float l21 = l21d11 / d11;
        const float d22 = (b4 - b2 * b2) - l21d11 * l21;
        // The polynomial c0 + c1 z + c2 z^2 whose roots, with z0, carry the canonical distribution.
        float c1 = z0 - b1;
        float c2 = z0 * z0 - b2 - l21 * c1;
        c1 = c1 / d11;
        c2 = c2 / d22;
        c1 = c1 - l21 * c2;
        const float c0 = 1.0f - (c1 * b1 + c2 * b2);
        const float p = c1 / c2, q = c0 / c2;
        const float r = std::sqrt(0.25f * p * p - q);
        const float z1 = -0.5f * p - r, z2 = -0.5f * p + r;
        // The interpolating polynomial of the weights (overestimation at z0, 1 in front, 0 behind),
        // applied to the moments.
        const float f0 = parameters_.overestimation, f1 = z1 < z0 ? 1.0f : 0.0f, f2 = z2 < z0 ? 1.0f : 0.0f;
        const float f01 = (f1 - f0) / (z1 - z0), f12 = (f2 - f1) / (z2 - z1), f012 = (f12 - f01) / (z2 - z0);
        const float q2 = f012, q1 = (f01 - f012 * z1) - q2 * z0;
        const float q0 = f0 - (f01 - f012 * z1) * z0;
        const float share = q0 + b1 * q1 + b2 * q2;
        // Where rounding still leaves no solution (a root on the query), the share the weights give
        // every point at the query: 0 for the lower bound, 1 for the upper, so a bound stays one.
        return b0 * (std::isfinite(share) ? share : f0);
    }

    /// The GLSL twin (shaders/reconstruction/power_moments.glsl) and its parameters.
    static std::string glsl_defines() { return "#define HS_MOMENTS 4\n"; }
    template <class Set>
    void glsl_uniforms(Set&& set) const {
        set("hs_moment_overestimation", parameters_.overestimation);
        set("hs_moment_bias", parameters_.bias);
    }

private:
    power_moments_parameters parameters_;
};

} // namespace hairshadow
