#pragma once
/// @file
/// The three policy families of a shadow method, as concepts. docs/policies.md describes each member.

#include <hairshadow/placement/layer_position.hpp>

#include <array>
#include <bit>
#include <concepts>
#include <cstddef>
#include <span>
#include <string_view>
#include <type_traits>

namespace hairshadow {

namespace detail {
/// Reads every byte of T{} at compile time. T{} of an aggregate initialises its members, not its
/// padding, and reading a padding byte that std::bit_cast copied is not a constant expression: so a
/// call is a constant only where T has none.
template <class T>
constexpr bool every_byte_defined() {
    const auto bytes = std::bit_cast<std::array<unsigned char, sizeof(T)>>(T{});
    unsigned sum = 0;
    for (const unsigned char b : bytes) sum += b; // each byte read
    static_cast<void>(sum);
    return true;
}

} // namespace detail

/// A texel whose bytes are all values: no padding, and constant-initialisable. maps_hash reads a
/// texel's bytes, and a padding byte holds whatever a build's copy left there (a hash that would
/// depend on the builds run before it); detail::tail_bytes names the padding a struct would end with.
template <class T>
concept padding_free = std::is_trivially_copyable_v<T> && requires { typename std::bool_constant<detail::every_byte_defined<T>()>; };

/// Placement: which pre-passes run and where a depth falls among a texel's layers. The per-texel
/// steps take a texel's fragments as a span of `fragment` (from a fragment_buffer) or of
/// `optical_fragment` (the tiled build), read through `.depth` and fragment_optical_depth(f).
/// Required: the layers (layer_count, cumulative), the state (texel_state), the steps (prepare,
/// prepare_texel, assign) and the result (locate), and the GLSL snippet's name. Optional, with
/// their defaults: contiguous (false), global_bytes() (0), and the capabilities of
/// policies/capabilities.hpp.
template <class P>
concept placement_policy = std::default_initializable<P> && std::copyable<P> && requires(P p, const P cp, const depth_extent& extent,
                                                                                         std::span<const fragment> frags,
                                                                                         std::span<const optical_fragment> tile_frags,
                                                                                         typename P::texel_state& state, float depth) {
    { P::layer_count } -> std::convertible_to<int>;
    { P::cumulative } -> std::convertible_to<bool>;
    { P::glsl_name } -> std::convertible_to<std::string_view>;
    requires std::default_initializable<typename P::texel_state>;
    p.prepare(extent);
    cp.prepare_texel(frags, state);
    cp.prepare_texel(tile_frags, state);
    { cp.assign(state, depth) } -> std::same_as<int>;
    { cp.locate(state, depth) } -> std::same_as<layer_position>;
};

/// Accumulation: how each fragment's optical depth is summed and stored.
template <class A>
concept accumulation_policy = requires(typename A::sum_type s, typename A::value_type v, float b) {
    { A::add(s, b) } -> std::same_as<typename A::sum_type>;
    { A::combine(s, s) } -> std::same_as<typename A::sum_type>;
    { A::store(s) } -> std::same_as<typename A::value_type>;
    { A::decode(v) } -> std::same_as<float>;
    { A::glsl_name } -> std::convertible_to<std::string_view>;
};

/// Reconstruction: what a texel stores and how it turns into optical depth at a query depth.
/// Its steps are static functions, or members where the reconstruction holds parameters (then
/// prepare(light) may give it the light before a build).
template <class R, class P, class A>
concept reconstruction_policy =
    std::copyable<R> && requires(const R& r, const P& p, const typename P::texel_state& state, std::span<const fragment> frags, std::span<const optical_fragment> tile_frags,
             typename R::template storage<P, A>& out, const typename R::template storage<P, A>& in, float depth) {
        { R::template accepts<P> } -> std::convertible_to<bool>;
        { R::glsl_name } -> std::convertible_to<std::string_view>;
        r.template build<P, A>(p, state, frags, out);
        r.template build<P, A>(p, state, tile_frags, out);
        { r.template optical_depth<P, A>(p, state, in, depth) } -> std::same_as<float>;
    };

} // namespace hairshadow
