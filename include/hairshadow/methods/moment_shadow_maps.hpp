#pragma once
/// @file
/// Moment shadow maps for translucent occluders (Peters et al. 2016; Münstermann et al. 2018's
/// moment-based transparency): the total optical depth and M power moments of depth per texel (4, 6 or
/// 8), over the texel's depth range. The spec `msm[:M[:OVERESTIMATION]]`.

#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/reconstruction/power_moments.hpp>

namespace hairshadow {

/// Moment shadow maps: the depth range (depth_range's nearest and furthest fragment, which bound z)
/// and M + 1 sums in float (the family takes no 8-bit accumulation: moment-based transparency keeps
/// moments in 16 bits at the least, and the bound needs their precision).
template <int M = 4>
using moment_shadow_maps = shadow_method<depth_range<1>, float_accumulation, power_moments<M>>;

/// The registration of moment shadow maps (methods/method_family.hpp).
struct moment_shadow_maps_family {
    static constexpr std::string_view name = "msm";
    static constexpr std::string_view grammar =
        "msm[:M[:OVERESTIMATION]] (moment shadow maps for translucent occluders: M = 4, 6 or 8 power moments, 4 by default; the "
        "weight of the query's own depth in [0, 1], 0.25 by default as moment-based transparency, 0 for the lower bound)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<moment_shadow_maps<4>>{"msm", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<moment_shadow_maps<4>>{"msm:4:0", in_compare},
                                                     spec_example<moment_shadow_maps<6>>{"msm:6", in_compare},
                                                     spec_example<moment_shadow_maps<8>>{"msm:8", in_compare});
    static constexpr std::array<std::string_view, 0> keywords{};
    using sizes = size_list<4, 6, 8>;

    static void check(const spec_fields& f) {
        if (f.size() > 2) throw f.bad("msm takes at most M and OVERESTIMATION");
        if (f.size() >= 1 && !sizes::contains(f.whole(0))) throw f.bad("msm needs M = 4, 6 or 8 power moments");
        f.checked([&] { parameters(f).check(); });
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        const int m = f.size() >= 1 ? f.whole(0) : 4;
        return with_size<sizes>(m, [&](auto size) { visit(moment_shadow_maps<size()>(depth_range<1>(), power_moments<size()>(parameters(f)))); });
    }

private:
    static power_moments_parameters parameters(const spec_fields& f) {
        power_moments_parameters p;
        if (f.size() == 2) p.overestimation = f.real(1, "overestimation");
        return p;
    }
};

} // namespace hairshadow
