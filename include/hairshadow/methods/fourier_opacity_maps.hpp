#pragma once
/// @file
/// Fourier opacity maps (Jansen & Bavoil 2010): C Fourier coefficients of each texel's absorption,
/// over the texel's depth range. The spec `fom[:C[:sigma]]`.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/reconstruction/fourier_series.hpp>

namespace hairshadow {

/// Fourier opacity maps: the depth range (depth_range's nearest and furthest fragment, which place
/// the period) and C coefficients summed in float, or in emulated 8 bits (each signed coefficient
/// stored as steps of b (1 + cos) / 2 or b (1 + sin) / 2 beside a_0's b: detail/depth_projection.hpp).
template <int C = 7, class Accumulation = float_accumulation>
using fourier_opacity_maps = shadow_method<depth_range<1>, Accumulation, fourier_series<C>>;

/// The registration of Fourier opacity maps (methods/method_family.hpp).
struct fourier_opacity_maps_family {
    static constexpr std::string_view name = "fom";
    static constexpr std::string_view grammar =
        "fom[:C[:sigma]] (Jansen & Bavoil's Fourier opacity maps: C = 3, 5, 7, 11 or 15 coefficients, 7 by default; sigma damps "
        "each harmonic by Lanczos' sigma factor)";
    static constexpr bool takes_accumulation = true;
    static constexpr auto examples = std::make_tuple(spec_example<fourier_opacity_maps<7>>{"fom", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<fourier_opacity_maps<7>>{"fom:7:sigma", in_compare},
                                                     spec_example<fourier_opacity_maps<15>>{"fom:15"},
                                                     spec_example<fourier_opacity_maps<7, emulated_8bit>>{"fom:7:8bit", in_compare});
    static constexpr auto keywords = std::to_array<std::string_view>({"sigma"});
    using sizes = size_list<3, 5, 7, 11, 15>;

    static void check(const spec_fields& f) {
        if (f.size() > 2) throw f.bad("fom takes at most C and sigma");
        if (f.size() >= 1 && !sizes::contains(f.whole(0))) throw f.bad("fom needs C = 3, 5, 7, 11 or 15");
        if (f.size() == 2 && f[1] != "sigma") throw f.bad("fom's second field can only be sigma");
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        const int c = f.size() >= 1 ? f.whole(0) : 7;
        const bool damped = f.size() == 2;
        return with_size<sizes>(c, [&](auto size) {
            visit(fourier_opacity_maps<size(), Accumulation>(depth_range<1>(), fourier_series<size()>(damped)));
        });
    }
};

} // namespace hairshadow
