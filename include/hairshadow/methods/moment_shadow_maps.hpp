#pragma once
/// @file
/// Moment shadow maps for translucent occluders (Peters et al. 2016; Münstermann et al. 2018's
/// moment-based transparency): the total optical depth and four power moments of depth per texel,
/// over the texel's depth range. The spec `msm[:4[:OVERESTIMATION]]`.

#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/reconstruction/power_moments.hpp>

namespace hairshadow {

/// Moment shadow maps: the depth range (depth_range's nearest and furthest fragment, which bound z)
/// and five sums in float (signed moments: no 8-bit accumulation).
using moment_shadow_maps = shadow_method<depth_range<1>, float_accumulation, power_moments>;

/// The registration of moment shadow maps (methods/method_family.hpp).
struct moment_shadow_maps_family {
    static constexpr std::string_view name = "msm";
    static constexpr std::string_view grammar =
        "msm[:4[:OVERESTIMATION]] (moment shadow maps for translucent occluders: 4 power moments; the weight of the query's own "
        "depth in [0, 1], 0.25 by default as moment-based transparency, 0 for the lower bound)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<moment_shadow_maps>{"msm", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<moment_shadow_maps>{"msm:4:0", in_compare});
    static constexpr std::array<std::string_view, 0> keywords{};

    static void check(const spec_fields& f) {
        if (f.size() > 2) throw f.bad("msm takes at most M and OVERESTIMATION");
        if (f.size() >= 1 && f.whole(0) != 4) throw f.bad("msm needs M = 4 power moments");
        f.checked([&] { parameters(f).check(); });
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        visit(moment_shadow_maps(depth_range<1>(), power_moments(parameters(f))));
        return true;
    }

private:
    static power_moments_parameters parameters(const spec_fields& f) {
        power_moments_parameters p;
        if (f.size() == 2) p.overestimation = f.real(1, "overestimation");
        return p;
    }
};

} // namespace hairshadow
