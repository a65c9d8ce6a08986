#pragma once
/// @file
/// Approximate deep shadow maps, as AMD TressFX ships them, and our variant with each texel's fibre
/// density measured. The spec `adsm[:SPACING:RADIUS:ALPHA[:MAX]]` or `adsm:auto`.

#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/placement/per_pixel_depth.hpp>
#include <hairshadow/reconstruction/fibre_density.hpp>

namespace hairshadow {

/// Approximate deep shadow maps, as AMD TressFX ships them: one depth map (deep opacity maps' z0, no
/// layers) and a constant density of fibres behind the first (fibre_density_parameters).
using approximate_deep_shadow_maps = shadow_method<per_pixel_depth<1>, float_accumulation, fibre_density<fibre_density_source::fixed>>;

/// Approximate deep shadow maps with each texel's density measured: occupancy maps' depth range and
/// the texel's summed optical depth (one opacity layer), spread over its fragment count.
using measured_density_shadow_maps = shadow_method<depth_range<1>, float_accumulation, fibre_density<fibre_density_source::measured>>;

/// The registration of both (methods/method_family.hpp): `adsm` with TressFX's parameters, or given
/// ones, and `adsm:auto` with each texel's measured density.
struct approximate_deep_shadow_maps_family {
    static constexpr std::string_view name = "adsm";
    static constexpr std::string_view grammar =
        "adsm[:SPACING:RADIUS:ALPHA[:MAX]] (TressFX's approximate deep shadow maps: fibre spacing in radii, fibre radius in world "
        "units, fibre alpha, and optionally a cap on the fibres counted, a whole number; default 0.4:0.0021:0.35 and no cap, as "
        "TressFX's shader) | adsm:auto (each texel's measured fibre density)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<approximate_deep_shadow_maps>{"adsm", in_compare | in_bench | in_figure},
                                                     spec_example<measured_density_shadow_maps>{"adsm:auto", in_compare | in_bench});
    static constexpr auto keywords = std::to_array<std::string_view>({"auto"});

    /// The fibre parameters of valid fields (TressFX's where none are given).
    static fibre_density_parameters parameters(const spec_fields& f) {
        fibre_density_parameters p;
        if (f.size() < 3) return p;
        p.spacing = f.real(0, "fibre spacing");
        p.radius = f.real(1, "fibre radius");
        p.alpha = f.real(2, "fibre alpha");
        if (f.size() == 4) {
            const int cap = f.whole(3);
            if (cap < 1) throw f.bad("the fibre cap must be at least one fibre");
            p.max_fibres = float(cap);
        }
        return p;
    }
    static void check(const spec_fields& f) {
        if (f.size() == 1) {
            if (f[0] != "auto") throw f.bad("adsm takes auto or SPACING:RADIUS:ALPHA[:MAX]");
            return;
        }
        if (f.size() != 0 && f.size() != 3 && f.size() != 4) throw f.bad("adsm takes auto or SPACING:RADIUS:ALPHA[:MAX]");
        f.checked([&] { parameters(f).check(); });
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        if (f.size() == 1) visit(measured_density_shadow_maps());
        else visit(approximate_deep_shadow_maps(per_pixel_depth<1>(), fibre_density<>(parameters(f))));
        return true;
    }
};

} // namespace hairshadow
