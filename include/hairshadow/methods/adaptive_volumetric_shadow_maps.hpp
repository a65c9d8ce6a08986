#pragma once
/// @file
/// Adaptive volumetric shadow maps (Salvi et al. 2010): at most N nodes of a piecewise-linear
/// transmittance per texel, a lossy deep shadow map. The spec `avsm[:N]`.

#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/planar_slices.hpp>
#include <hairshadow/reconstruction/adaptive_nodes.hpp>

namespace hairshadow {

/// Adaptive volumetric shadow maps: N nodes (depth, optical depth) per texel, 8 bytes each. The nodes
/// need no layers: the placement is one uniform slice with no per-texel state, which the
/// reconstruction ignores, and the sums are the nodes' own (float: no 8-bit accumulation).
template <int N = 8>
using adaptive_volumetric_shadow_maps = shadow_method<uniform_slices<1>, float_accumulation, adaptive_nodes<N>>;

/// The registration of adaptive volumetric shadow maps (methods/method_family.hpp).
struct adaptive_volumetric_shadow_maps_family {
    static constexpr std::string_view name = "avsm";
    static constexpr std::string_view grammar =
        "avsm[:N] (adaptive volumetric shadow maps: at most N = 4, 8 or 16 nodes of transmittance a texel, 8 by default, "
        "fragments inserted in depth order)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<adaptive_volumetric_shadow_maps<8>>{"avsm", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<adaptive_volumetric_shadow_maps<4>>{"avsm:4", in_compare},
                                                     spec_example<adaptive_volumetric_shadow_maps<16>>{"avsm:16", in_compare});
    static constexpr std::array<std::string_view, 0> keywords{};
    using sizes = size_list<4, 8, 16>;

    static void check(const spec_fields& f) {
        if (f.size() > 1) throw f.bad("avsm takes at most N");
        if (f.size() == 1 && !sizes::contains(f.whole(0))) throw f.bad("avsm needs N = 4, 8 or 16 nodes");
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        const int n = f.size() == 1 ? f.whole(0) : 8;
        return with_size<sizes>(n, [&](auto size) { visit(adaptive_volumetric_shadow_maps<size()>()); });
    }
};

} // namespace hairshadow
