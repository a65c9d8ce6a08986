#pragma once
/// @file
/// Compositions no paper describes, and the registrations of those the specs name (`docc:S:B`,
/// `rosm:N`).

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/deep_opacity_maps.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/occupancy_maps.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/placement/per_pixel_depth.hpp>
#include <hairshadow/reconstruction/interpolation.hpp>
#include <hairshadow/reconstruction/occupancy_bitcount.hpp>

namespace hairshadow {

/// Deep opacity maps accumulated the way an RGBA8 target would (Kim & Neumann's 8-bit buffers).
template <int K>
using deep_opacity_maps_8bit = deep_opacity_maps<K, emulated_8bit>;

/// Occupancy bits and slabs in slices that start at each texel's first fragment and span a fixed
/// depth (deep opacity maps' layers) instead of the texel's own range.
template <int S, int B>
using deep_occupancy_maps = shadow_method<per_pixel_depth<S, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation,
                                          occupancy_bitcount<B>>;

/// Opacity maps interpolated in each texel's own depth range (occupancy maps' placement).
template <int N>
using range_opacity_maps = shadow_method<depth_range<N>, float_accumulation, interpolation>;

/// The registration of deep occupancy maps (methods/method_family.hpp).
struct deep_occupancy_maps_family {
    static constexpr std::string_view name = "docc";
    static constexpr std::string_view grammar = "docc:S:B (hybrid: occupancy slices from each texel's first fragment)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<deep_occupancy_maps<128, 4>>{"docc:128:4", in_compare});
    static constexpr std::array<std::string_view, 0> keywords{};

    static void check(const spec_fields& f) { detail::occupancy_sizes::check(f, name); }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        return detail::occupancy_sizes::with_sizes(f, [&](auto s, auto b) { visit(deep_occupancy_maps<s(), b()>()); });
    }
};

/// The registration of range opacity maps (methods/method_family.hpp).
struct range_opacity_maps_family {
    static constexpr std::string_view name = "rosm";
    static constexpr std::string_view grammar = "rosm:N (hybrid: opacity maps in each texel's depth range, N = 4, 8, ..., 256)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<range_opacity_maps<16>>{"rosm:16"});
    static constexpr std::array<std::string_view, 0> keywords{};
    using sizes = size_list<4, 8, 16, 32, 64, 128, 256>;

    static void check(const spec_fields& f) {
        if (f.size() != 1) throw f.bad("rosm takes N");
        if (!sizes::contains(f.whole(0))) throw f.bad("rosm needs N = 4, 8, ..., 256");
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        return with_size<sizes>(f.whole(0), [&](auto n) { visit(range_opacity_maps<n()>()); });
    }
};

} // namespace hairshadow
