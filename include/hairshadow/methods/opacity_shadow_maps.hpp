#pragma once
/// @file
/// Opacity shadow maps (Kim & Neumann 2001): N planar slices, summed, interpolated linearly. The spec
/// `osm:N[:uniform|gamma]`.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/planar_slices.hpp>
#include <hairshadow/reconstruction/interpolation.hpp>

namespace hairshadow {

/// Opacity shadow maps (Kim & Neumann 2001): N planar slices, float sums, linear interpolation.
/// @tparam N number of maps
/// @tparam Spacing uniform_spacing (Fig. 3a) or gamma_spacing (Fig. 3c)
template <int N, class Spacing = uniform_spacing, class Accumulation = float_accumulation>
using opacity_shadow_maps = shadow_method<planar_slices<N, Spacing>, Accumulation, interpolation>;

/// The registration of opacity shadow maps (methods/method_family.hpp).
struct opacity_shadow_maps_family {
    static constexpr std::string_view name = "osm";
    static constexpr std::string_view grammar = "osm:N[:uniform|gamma] (N = 1, 2, 4, ..., 512)";
    static constexpr bool takes_accumulation = true;
    static constexpr auto examples = std::make_tuple(spec_example<opacity_shadow_maps<16>>{"osm:16", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<opacity_shadow_maps<64>>{"osm:64", in_compare | in_bench},
                                                     spec_example<opacity_shadow_maps<256>>{"osm:256", in_compare | in_figure},
                                                     spec_example<opacity_shadow_maps<8, gamma_spacing>>{"osm:8:gamma"},
                                                     spec_example<opacity_shadow_maps<4, uniform_spacing, emulated_8bit>>{"osm:4:8bit"});
    static constexpr auto keywords = std::to_array<std::string_view>({"uniform", "gamma"});
    using sizes = size_list<1, 2, 4, 8, 16, 32, 64, 128, 256, 512>;

    static void check(const spec_fields& f) {
        if (f.size() < 1 || f.size() > 2) throw f.bad("osm takes N and an optional spacing");
        if (!sizes::contains(f.whole(0))) throw f.bad("osm needs N = 1, 2, 4, ..., 512");
        if (f.size() == 2 && f[1] != "gamma" && f[1] != "uniform") throw f.bad("osm spacing must be uniform or gamma");
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        const bool gamma = f.size() == 2 && f[1] == "gamma";
        return with_size<sizes>(f.whole(0), [&](auto n) {
            if (gamma) visit(opacity_shadow_maps<n(), gamma_spacing, Accumulation>());
            else visit(opacity_shadow_maps<n(), uniform_spacing, Accumulation>());
        });
    }
};

} // namespace hairshadow
