#pragma once
/// @file
/// Reconstruction by power moments: moment shadow maps for translucent occluders (Peters et al. 2016)
/// as moment-based order-independent transparency computes them (Münstermann et al. 2018). Each
/// texel keeps its total optical depth b_0 = sum b_i and the optical-depth-weighted power moments
/// sum b_i z_i^j, j = 1 .. M (M = 4, 6 or 8), of depth z in [-1, 1] (here the texel's depth range: -1
/// at its nearest fragment, 1 at its furthest; reconstruction/detail/depth_projection.hpp). A query
/// at z normalises the moments by b_0, pulls them toward a fixed vector by a small bias (a singular
/// Hankel matrix otherwise: k sheets of hair are k depths), and solves for the canonical distribution
/// with one support point at z: z and the M/2 roots of a polynomial of degree M/2 (Hamburger MSM; a
/// quadratic for 4 moments, a cubic for 6, a quartic for 8). The weight of its points in front of z,
/// plus `overestimation` times the weight at z, is the share of b_0 in front. Overestimation 0 gives
/// the sharpest lower bound of that share over every distribution with these moments (a bound on the
/// exact optical depth from below, which the bias loosens a little), 1 the upper bound; MBOIT's 0.25
/// is the default. Every operation is float, in one order that the GLSL twin repeats; docs/methods.md
/// checks the bound on the test models.

#include <hairshadow/core/error.hpp>
#include <hairshadow/reconstruction/detail/depth_projection.hpp>
#include <hairshadow/reconstruction/detail/polynomial_roots.hpp>

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

namespace hairshadow {

/// What the moment reconstruction takes.
struct power_moments_parameters {
    /// The weight the canonical distribution's point at the query depth counts with: 0 the lower
    /// bound, 1 the upper, MBOIT's 0.25 by default.
    float overestimation = 0.25f;
    /// How far the normalised moments are pulled toward MBOIT's bias vector for M power moments in
    /// 32-bit floats (power_moments<M>::bias_vector). Unset: MBOIT's bias for M moments in 32-bit
    /// floats, 5e-7, 5e-6 and 5e-5 for 4, 6 and 8 (the values of the authors' code as ported in
    /// chrismile/PixelSyncOIT, src/OIT/OIT_MBOIT.cpp); at them the bound holds within 1e-3 of a
    /// texel's total on Sintel and on sheets of strands (tests/test_moment_shadow_maps.cpp).
    std::optional<float> bias{};
    /// Throws argument_error unless the overestimation is in [0, 1] and a bias given is in [1e-7, 1]:
    /// with less, a texel of two depths (its range's ends, z = -1 and 1) leaves the Hankel matrix singular.
    void check() const {
        if (!(overestimation >= 0.0f && overestimation <= 1.0f)) throw argument_error("power moments: the overestimation must be in [0, 1]");
        if (bias && !(*bias >= 1e-7f && *bias <= 1.0f)) throw argument_error("power moments: the bias must be in [1e-7, 1]");
    }
    friend bool operator==(const power_moments_parameters&, const power_moments_parameters&) = default;
};

/// Optical depth from the total and M power moments of each texel's absorption.
/// @tparam M power moments: 4, 6 or 8
template <int M = 4>
class power_moments : public detail::depth_projection<power_moments<M>, M + 1> {
    static_assert(M == 4 || M == 6 || M == 8, "power_moments takes 4, 6 or 8 moments");
    static constexpr int n = M / 2; // the canonical distribution's support points besides the query

public:
    static constexpr int moments = M;
    /// b_0 = b (detail/depth_projection.hpp's encoding for an 8-bit accumulation).
    static constexpr float terms_per_optical_depth = 1.0f;
    static constexpr std::string_view name = "power_moments";
    static constexpr std::string_view glsl_name = "reconstruction/power_moments";
    /// MBOIT's bias vectors for 32-bit floats (the moments of a distribution the biased ones are
    /// pulled toward; odd moments 0), as in chrismile/PixelSyncOIT's Data/Shaders/MBOIT/MomentOIT.glsl.
    static constexpr std::array<float, std::size_t(M + 1)> bias_vector = [] {
        if constexpr (M == 4) return std::array<float, 5>{1.0f, 0.0f, 0.375f, 0.0f, 0.375f};
        else if constexpr (M == 6) return std::array<float, 7>{1.0f, 0.0f, 0.48f, 0.0f, 0.451f, 0.0f, 0.45f};
        else return std::array<float, 9>{1.0f, 0.0f, 0.75f, 0.0f, 0.67666666666666664f, 0.0f, 0.63f, 0.0f, 0.60030303030303034f};
    }();
    /// MBOIT's bias for M moments in 32-bit floats (power_moments_parameters::bias).
    static constexpr float default_bias = M == 4 ? 5e-7f : M == 6 ? 5e-6f : 5e-5f;

    power_moments() = default;
    explicit power_moments(const power_moments_parameters& parameters) : parameters_(parameters) { parameters.check(); }
    const power_moments_parameters& parameters() const noexcept { return parameters_; }
    /// The bias the reconstruction uses: the parameters', or MBOIT's for M moments.
    float bias() const noexcept { return parameters_.bias.value_or(default_bias); }

    /// Adds b and b z, b z^2, .. b z^M at z = 2 s - 1.
    static void project(float s, float b, double* terms) noexcept {
        const float z = 2.0f * s - 1.0f;
        float power = b;
        terms[0] += double(b);
        for (int j = 1; j <= M; ++j) {
            power = power * z;
            terms[j] += double(power);
        }
    }
    static float total_optical_depth(const float* stored) noexcept { return stored[0]; }

    /// b_0 times the share of it in front of position s (Hamburger MSM, in float as the GLSL twin).
    float series_optical_depth(const float* stored, float s) const noexcept {
        // The biased normalised moments, b[0] = 1.
        const float b0 = stored[0], bias = this->bias(), keep = 1.0f - bias;
        std::array<float, std::size_t(M + 1)> b{};
        b[0] = 1.0f;
        for (int j = 1; j <= M; ++j) {
            b[std::size_t(j)] = keep * (stored[j] / b0);
            if (j % 2 == 0) b[std::size_t(j)] = b[std::size_t(j)] + bias * bias_vector[std::size_t(j)];
        }
        const float z0 = 2.0f * s - 1.0f;
        // An LDL^T factorisation of the Hankel matrix H_ij = b_(i+j), i, j = 0 .. n (e = l d).
        float l[n + 1][n + 1] = {}, e[n + 1][n + 1] = {}, d[n + 1] = {};
        d[0] = 1.0f;
        for (int i = 1; i <= n; ++i) l[i][0] = e[i][0] = b[std::size_t(i)];
        for (int j = 1; j <= n; ++j) {
            float djj = b[std::size_t(2 * j)];
            for (int k = 0; k < j; ++k) djj = djj - e[j][k] * l[j][k];
            d[j] = djj;
            for (int i = j + 1; i <= n; ++i) {
                float eij = b[std::size_t(i + j)];
                for (int k = 0; k < j; ++k) eij = eij - e[i][k] * l[j][k];
                e[i][j] = eij;
                l[i][j] = eij / djj;
            }
        }
        // c = H^-1 (1, z0, .. z0^n): the coefficients of the polynomial whose roots, with z0, carry
        // the canonical distribution.
        float c[n + 1];
        c[0] = 1.0f;
        float power = 1.0f;
        for (int i = 1; i <= n; ++i) {
            power = power * z0;
            float ci = power;
            for (int k = 0; k < i; ++k) ci = ci - l[i][k] * c[k];
            c[i] = ci;
        }
        for (int i = 1; i <= n; ++i) c[i] = c[i] / d[i];
        for (int i = n - 1; i >= 0; --i) {
            float sum = l[i + 1][i] * c[i + 1];
            for (int j = i + 2; j <= n; ++j) sum = sum + l[j][i] * c[j];
            c[i] = c[i] - sum;
        }
        // The support points and their weights (overestimation at z0, 1 in front, 0 behind).
        float z[n + 1], f[n + 1];
        z[0] = z0;
        f[0] = parameters_.overestimation;
        const auto roots = detail::real_roots<n>(c);
        for (int i = 1; i <= n; ++i) {
            z[i] = roots[std::size_t(i - 1)];
            f[i] = z[i] < z0 ? 1.0f : 0.0f;
        }
        // The polynomial interpolating the weights at the points (Newton's divided differences, then
        // its monomial coefficients), applied to the moments.
        for (int order = 1; order <= n; ++order)
            for (int i = n; i >= order; --i) f[i] = (f[i] - f[i - 1]) / (z[i] - z[i - order]);
        float q[n + 1] = {};
        q[0] = f[n];
        for (int k = n - 1, degree = 0; k >= 0; --k, ++degree) {
            q[degree + 1] = q[degree];
            for (int i = degree; i >= 1; --i) q[i] = q[i - 1] - q[i] * z[k];
            q[0] = f[k] - q[0] * z[k];
        }
        float share = q[0];
        for (int k = 1; k <= n; ++k) share = share + b[std::size_t(k)] * q[k];
        // Where rounding still leaves no solution (a root on the query), the share the weights give
        // every point at the query: 0 for the lower bound, 1 for the upper, so a bound stays one.
        return b0 * (std::isfinite(share) ? share : parameters_.overestimation);
    }

    /// The GLSL twin (shaders/reconstruction/power_moments.glsl) and its parameters.
    static std::string glsl_defines() { return "#define HS_MOMENTS " + std::to_string(M) + "\n"; }
    template <class Set>
    void glsl_uniforms(Set&& set) const {
        set("hs_moment_overestimation", parameters_.overestimation);
        set("hs_moment_bias", bias());
        // The pull on moment 2k, the bias times the bias vector, computed here so that GL adds the
        // CPU's floats.
        for (int k = 1; k <= n; ++k)
            set("hs_moment_pull", bias() * bias_vector[std::size_t(2 * k)], k - 1);
    }

private:
    power_moments_parameters parameters_;
};

} // namespace hairshadow
