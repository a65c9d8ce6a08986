#pragma once
/// @file
/// The fast paths of the tiled build, each a named capability that a policy (or a composition of
/// policies) has by declaring a few optional members. A policy that has none of them is still a whole
/// method: it builds by the grouped build (each texel's fragments gathered, then prepare_texel and
/// build), on every CPU. Each capability only makes the same maps faster, bit for bit; the build plan
/// (methods/detail/build_plan.hpp) picks the path from these and nothing else. docs/policies.md,
/// "Capabilities", says what each member must do; tests/test_capabilities.cpp states, with
/// STATIC_REQUIRE, which of the library's compositions has which.
///
/// | capability                 | what the composition declares                                   | the path it opens |
/// |----------------------------|-----------------------------------------------------------------|-------------------|
/// | streams_tiles              | texel_state_from; accumulator, accumulate, finish               | the streamed build: a tile's fragments reduced where the walk left them |
/// | order_free_maps            | fragment_order_free in placement and reconstruction             | the AVX-512 walk in any order (one alpha, no depth of -0) |
/// | assigns_each_avx512        | assign_each_avx512                                              | the streamed build's layers sixteen fragments at a time |
/// | prepares_texel_avx512      | prepare_texel_avx512                                            | the grouped build's pre-pass sixteen at a time |
/// | assigns_texel_avx512       | assign_texel_avx512                                             | the grouped build's layers sixteen at a time |
/// | counts_texel_avx512        | count_texel_avx512                                              | a texel of one b counted, not summed |
/// | builds_from_depths_avx512  | prepare_texel_depths_avx512; build_from_depths                  | a map of one b grouped as depths alone (half the bytes) |
///
/// The AVX-512 members exist only where the vector paths are compiled (raster/instruction_set.hpp:
/// HAIRSHADOW_AVX512_WALK); elsewhere their capabilities are false and the scalar paths run.

#include <hairshadow/raster/fragment.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace hairshadow::detail {

/// Whether a composition can be built without grouping (methods/detail/streamed_tile.hpp): its placement's
/// texel state comes from the texel's nearest and furthest fragment, and its reconstruction builds
/// in pieces, a fragment at a time.
template <class Placement, class Accumulation, class Reconstruction>
concept streams_tiles = requires(const Placement& p, typename Placement::texel_state& s,
                                 typename Reconstruction::template accumulator<Placement, Accumulation>& a,
                                 typename Reconstruction::template storage<Placement, Accumulation>& out) {
    p.texel_state_from(0.0f, 0.0f, s);
    Reconstruction::template accumulate<Placement, Accumulation>(a, 0, 0.0f);
    Reconstruction::template finish<Placement, Accumulation>(a, out);
};

/// Whether a composition's maps are the same for any order of each texel's fragments where they all
/// share one optical depth and no depth is -0 (both placement and reconstruction say so): then a
/// tile may be walked in any order (fragment_order::any). The depth extent is a minimum and a
/// maximum, the same for any order once +0 and -0 cannot meet; every sum adds the same b, so that
/// the sum of n of them is one number; bits are ORed; density clustering's k-means sums are integers.
template <class Placement, class Reconstruction>
concept order_free_maps = Placement::fragment_order_free && Reconstruction::fragment_order_free;

/// Whether `Placement` assigns sixteen fragments of many texels at a time.
template <class Placement>
concept assigns_each_avx512 = requires(const Placement& p, const typename Placement::texel_state* states, std::span<const std::uint32_t> texels,
                                       std::span<const float> depths, std::int32_t* layers) {
    p.assign_each_avx512(states, texels, depths, layers);
};

/// Whether `Placement` has a vector pre-pass for one texel's optical fragments.
template <class Placement>
concept prepares_texel_avx512 = requires(const Placement& p, std::span<const optical_fragment> fragments, typename Placement::texel_state& s) {
    p.prepare_texel_avx512(fragments, s);
};

/// Whether `Placement` assigns one texel's optical fragments sixteen at a time.
template <class Placement>
concept assigns_texel_avx512 = requires(const Placement& p, const typename Placement::texel_state& s, std::span<const optical_fragment> fragments,
                                        std::int32_t* layers) {
    p.assign_texel_avx512(s, fragments, layers);
};

/// Whether `Placement` counts one texel's optical fragments in its layers sixteen at a time.
template <class Placement>
concept counts_texel_avx512 = requires(const Placement& p, const typename Placement::texel_state& s, std::span<const optical_fragment> fragments,
                                       std::array<std::uint32_t, std::size_t(Placement::layer_count)>& counts) {
    p.count_texel_avx512(s, fragments, counts);
};

/// Whether a composition builds a texel whose fragments share one optical depth from their depths
/// alone (tile_fragments::group_depths): a placement with prepare_texel_depths_avx512 and a
/// reconstruction with build_from_depths.
template <class Placement, class Accumulation, class Reconstruction>
concept builds_from_depths_avx512 = requires(const Placement& p, typename Placement::texel_state& s, std::span<const float> depths,
                                             typename Reconstruction::template storage<Placement, Accumulation>& out) {
    p.prepare_texel_depths_avx512(depths, 0.0f, s);
    Reconstruction::template build_from_depths<Placement, Accumulation>(p, s, depths, 0.0f, out);
};

/// A composition's capabilities in one place: what tests state per method, and what a user reads to
/// see why a method builds as it does.
template <class Placement, class Accumulation, class Reconstruction>
struct capabilities {
    static constexpr bool streams = streams_tiles<Placement, Accumulation, Reconstruction>;
    static constexpr bool order_free = order_free_maps<Placement, Reconstruction>;
    static constexpr bool assigns_each = assigns_each_avx512<Placement>;
    static constexpr bool prepares_texel = prepares_texel_avx512<Placement>;
    static constexpr bool assigns_texel = assigns_texel_avx512<Placement>;
    static constexpr bool counts_texel = counts_texel_avx512<Placement>;
    static constexpr bool from_depths = builds_from_depths_avx512<Placement, Accumulation, Reconstruction>;
};

/// The capabilities of a shadow_method.
template <class Method>
using capabilities_of = capabilities<typename Method::placement_type, typename Method::accumulation_type, typename Method::reconstruction_type>;

} // namespace hairshadow::detail
