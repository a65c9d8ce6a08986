#pragma once
/// @file
/// Where a depth falls among a texel's layers: the helpers every placement shares.

#include <hairshadow/raster/depth_extent.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

namespace hairshadow {

/// A query depth's place among `layer_count` layers: index -1 is in front of the first layer,
/// index layer_count behind the last; otherwise `fraction` in [0, 1] says how far into layer `index`.
struct layer_position {
    int index;
    float fraction;
};

/// `values` as a GLSL array of their bits, "uint[](0x00000000u, ...)", for a GLSL twin to read with
/// uintBitsToFloat: the CPU's constants bit for bit, where a division in the shader would cost an
/// exact division (hs_div_rn) a fragment and a constant one may be folded another way.
template <std::size_t N>
std::string glsl_float_bits(const std::array<float, N>& values) {
    std::string out = "uint[](";
    for (std::size_t i = 0; i < N; ++i) {
        char word[16];
        std::snprintf(word, sizeof word, "%s0x%08xu", i == 0 ? "" : ", ", unsigned(std::bit_cast<std::uint32_t>(values[i])));
        out += word;
    }
    return out + ")";
}

/// Whether a placement's layers tile a depth interval without gaps (P::contiguous; false where it
/// does not say): occupancy_bitcount needs it.
template <class P>
constexpr bool contiguous_layers() noexcept {
    if constexpr (requires { P::contiguous; }) return P::contiguous;
    else return false;
}

/// Bytes of a placement's global state (P::global_bytes(); none where it does not say).
template <class P>
constexpr std::size_t placement_global_bytes() noexcept {
    if constexpr (requires { P::global_bytes(); }) return P::global_bytes();
    else return 0;
}

namespace detail {
/// Moves an estimated layer index to the k in [0, last] with boundary(k) <= depth < boundary(k + 1).
/// Closed forms for the layer of a depth can miss by one where rounding meets a boundary; settling
/// against the boundary depths themselves makes fragments and queries agree exactly.
template <class Boundary>
int settle_layer(float estimate, int last, float depth, Boundary boundary) noexcept {
    int k = estimate > 0.0f ? int(std::min(estimate, float(last))) : 0; // NaN and negatives give 0
    while (k > 0 && depth < boundary(k)) --k;
    while (k < last && depth >= boundary(k + 1)) ++k;
    return k;
}

/// placement.assign(state, depth) for the fragments of one texel: the placement's own assigner(state)
/// where it has one (work done once per texel instead of once per fragment), else assign itself.
template <class Placement>
auto texel_assigner(const Placement& placement, const typename Placement::texel_state& state) noexcept {
    if constexpr (requires { placement.assigner(state); }) return placement.assigner(state);
    else return [&placement, &state](float depth) noexcept { return placement.assign(state, depth); };
}

/// Layer k's position for a depth between its boundaries lo and hi.
inline layer_position position_in(int k, float depth, float lo, float hi) noexcept {
    return {k, hi > lo ? std::clamp((depth - lo) / (hi - lo), 0.0f, 1.0f) : 0.0f};
}

/// The smallest float above `hi`, so that a half-open range [lo, end) holds a fragment at hi.
inline float just_above(float hi) noexcept { return std::nextafter(hi, std::numeric_limits<float>::infinity()); }
} // namespace detail

} // namespace hairshadow
