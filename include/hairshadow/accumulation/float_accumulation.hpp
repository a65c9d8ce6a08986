#pragma once
/// @file
/// Float accumulation: optical depths summed in 32-bit floats, as additive blending into RGBA32F does.

#include <bit>
#include <cstdint>
#include <string_view>

namespace hairshadow {

namespace detail {
/// x where `keep`, else +0, by a bit mask: no branch for the compiler to mispredict with.
inline float keep_if(bool keep, float x) noexcept {
    return std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) & (0u - std::uint32_t(keep)));
}
} // namespace detail

/// Sums each fragment's optical depth b = -ln(1 - alpha) in float; stores the sum as it is.
struct float_accumulation {
    using value_type = float;  ///< what a map texel stores
    using sum_type = float;    ///< what is summed while building
    static constexpr std::string_view name = "float";
    static constexpr std::string_view summary = "float sums";
    static constexpr std::string_view glsl_name = "accumulation/float";

    /// Adds one fragment's optical depth.
    static constexpr sum_type add(sum_type sum, float optical_depth) noexcept { return sum + optical_depth; }
    /// Adds two partial sums (prefix sums of layers).
    static constexpr sum_type combine(sum_type a, sum_type b) noexcept { return a + b; }
    /// The stored value of a sum.
    static constexpr value_type store(sum_type sum) noexcept { return sum; }
    /// The optical depth a stored value stands for.
    static constexpr float decode(value_type v) noexcept { return v; }
};

} // namespace hairshadow
