#pragma once
/// @file
/// Density clustering (Mertens et al. 2004): K k-means clusters of each texel's fragments as histogram
/// bins. The spec `dc:K`.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/clustered.hpp>
#include <hairshadow/reconstruction/interpolation.hpp>

namespace hairshadow {

/// Density clustering (Mertens et al. 2004): K k-means clusters per texel as histogram bins.
template <int K, class Accumulation = float_accumulation>
using density_clustering = shadow_method<clustered<K>, Accumulation, interpolation>;

/// The registration of density clustering (methods/method_family.hpp).
struct density_clustering_family {
    static constexpr std::string_view name = "dc";
    static constexpr std::string_view grammar = "dc:K (K = 1..8)";
    static constexpr bool takes_accumulation = true;
    static constexpr auto examples = std::make_tuple(spec_example<density_clustering<4>>{"dc:4", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<density_clustering<8, emulated_8bit>>{"dc:8:8bit"});
    static constexpr std::array<std::string_view, 0> keywords{};
    using sizes = size_list<1, 2, 3, 4, 5, 6, 7, 8>;

    static void check(const spec_fields& f) {
        if (f.size() != 1) throw f.bad("dc takes K");
        if (!sizes::contains(f.whole(0))) throw f.bad("dc needs K = 1..8");
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        return with_size<sizes>(f.whole(0), [&](auto k) { visit(density_clustering<k(), Accumulation>()); });
    }
};

} // namespace hairshadow
