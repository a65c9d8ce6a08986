#pragma once
/// @file
/// Deep opacity maps (Yuksel & Keyser 2008): K layers from each texel's first fragment. The spec
/// `dom:K`.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/per_pixel_depth.hpp>
#include <hairshadow/reconstruction/interpolation.hpp>

namespace hairshadow {

/// Deep opacity maps (Yuksel & Keyser 2008): K layers from each texel's first fragment.
template <int K, class Accumulation = float_accumulation>
using deep_opacity_maps = shadow_method<per_pixel_depth<K>, Accumulation, interpolation>;

/// The registration of deep opacity maps (methods/method_family.hpp).
struct deep_opacity_maps_family {
    static constexpr std::string_view name = "dom";
    static constexpr std::string_view grammar = "dom:K (K = 1..8)";
    static constexpr bool takes_accumulation = true;
    static constexpr auto examples = std::make_tuple(spec_example<deep_opacity_maps<3>>{"dom:3", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<deep_opacity_maps<4>>{"dom:4", in_compare},
                                                     spec_example<deep_opacity_maps<3, emulated_8bit>>{"dom:3:8bit", in_compare},
                                                     spec_example<deep_opacity_maps<4, emulated_8bit>>{"dom:4:8bit"});
    static constexpr std::array<std::string_view, 0> keywords{};
    using sizes = size_list<1, 2, 3, 4, 5, 6, 7, 8>;

    static void check(const spec_fields& f) {
        if (f.size() != 1) throw f.bad("dom takes K");
        if (!sizes::contains(f.whole(0))) throw f.bad("dom needs K = 1..8");
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        return with_size<sizes>(f.whole(0), [&](auto k) { visit(deep_opacity_maps<k(), Accumulation>()); });
    }
};

} // namespace hairshadow
