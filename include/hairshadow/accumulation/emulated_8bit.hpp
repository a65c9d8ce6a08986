#pragma once
/// @file
/// Emulated 8-bit accumulation (Kim & Neumann 2001, section 2): an RGBA8 target with additive blending.
/// Each fragment writes b / kappa, which GL converts to 8 bits (round to nearest) before the blend
/// adds it with saturation; a stored value q stands for the optical depth kappa * q / 255, with
/// exp(-kappa) = 2^-8 so that a full texel (q = 255) lets 1/256 of the light through.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string_view>

namespace hairshadow {

/// Every add quantised to 8 bits and saturated, as additive blending into an RGBA8 target does.
struct emulated_8bit {
    using value_type = std::uint8_t;
    using sum_type = std::int32_t; ///< saturated at 255 after every add, exactly as the blend does
    static constexpr std::string_view name = "8bit";
    static constexpr std::string_view summary = "emulated 8-bit accumulation";
    static constexpr std::string_view glsl_name = "accumulation/emulated_8bit";
    /// exp(-kappa) = 2^-8: kappa = 8 ln 2, about 5.545 (the paper rounds it to 5.56).
    static constexpr float kappa = 8.0f * std::numbers::ln2_v<float>;

    /// The 8-bit step a fragment of optical depth b adds: its output b / kappa in unorm8, rounded half
    /// away from zero (std::lround's rounding, computed inline as the GLSL twin computes it: the
    /// whole part, and one more where the fraction, exact for x in [0, 255], is at least a half; a
    /// call to lroundf cost a fifth of an 8-bit Fourier build).
    static std::int32_t quantise(float optical_depth) noexcept {
        const float unit = optical_depth / kappa;
        const float x = (unit > 0.0f ? std::min(unit, 1.0f) : 0.0f) * 255.0f; // NaN to 0, never an undefined conversion
        const auto whole = std::int32_t(x);
        return whole + (x - float(whole) >= 0.5f ? 1 : 0);
    }
    static sum_type add(sum_type sum, float optical_depth) noexcept { return std::min<sum_type>(sum + quantise(optical_depth), 255); }
    static constexpr sum_type combine(sum_type a, sum_type b) noexcept { return std::min<sum_type>(a + b, 255); }
    static constexpr value_type store(sum_type sum) noexcept { return value_type(std::min<sum_type>(sum, 255)); }
    static constexpr float decode(value_type v) noexcept { return kappa * float(v) / 255.0f; }
};

} // namespace hairshadow
