#pragma once
/// @file
/// Unreal Engine's hair-count deep shadows (HairStrands): K layers at power-law depths behind each
/// texel's first fragment, and T = A^max(0, count - 1). The spec `ue[:K[:ALPHA[:DISTRIBUTION]]]`.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/power_layers.hpp>
#include <hairshadow/reconstruction/hair_count.hpp>

namespace hairshadow {

/// Unreal Engine's hair-count deep shadows: power_layers (the layers' depths) and hair_count (the
/// look-up). Unreal ships K = 4, in one RGBA16F texel beside a depth map.
template <int K = 4, class Accumulation = float_accumulation>
using hair_count_deep_shadows = shadow_method<power_layers<K>, Accumulation, hair_count>;

/// The registration of hair-count deep shadows (methods/method_family.hpp).
struct hair_count_deep_shadows_family {
    static constexpr std::string_view name = "ue";
    static constexpr std::string_view grammar =
        "ue[:K[:ALPHA[:DISTRIBUTION]]] (Unreal Engine's hair-count deep shadows: K = 2, 4 or 8 layers, 4 by default; one hair's "
        "fragment alpha, 0.12 by default; the layer distribution in [0, 1], 0.5 by default) | ue:K:zero (the count from zero, "
        "without Unreal's - 1)";
    static constexpr bool takes_accumulation = true;
    static constexpr auto examples = std::make_tuple(spec_example<hair_count_deep_shadows<4>>{"ue", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<hair_count_deep_shadows<4>>{"ue:4"},
                                                     spec_example<hair_count_deep_shadows<8>>{"ue:8", in_compare},
                                                     spec_example<hair_count_deep_shadows<4, emulated_8bit>>{"ue:4:8bit"});
    static constexpr auto keywords = std::to_array<std::string_view>({"zero"});
    using sizes = size_list<2, 4, 8>;

    static void check(const spec_fields& f) {
        if (f.size() > 3) throw f.bad("ue takes at most K, ALPHA and DISTRIBUTION, or K:zero");
        if (f.size() >= 1 && !sizes::contains(f.whole(0))) throw f.bad("ue needs K = 2, 4 or 8");
        if (f.size() == 2 && f[1] == "zero") return;
        f.checked([&] {
            parameters(f).check();
            (void)power_layers<4>(distribution(f));
        });
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        const int k = f.size() >= 1 ? f.whole(0) : 4;
        return with_size<sizes>(k, [&](auto size) {
            visit(hair_count_deep_shadows<size(), Accumulation>(power_layers<size()>(distribution(f)), hair_count(parameters(f))));
        });
    }

private:
    static hair_count_parameters parameters(const spec_fields& f) {
        hair_count_parameters p;
        if (f.size() == 2 && f[1] == "zero") p.minus_one = false;
        else if (f.size() >= 2) p.hair_alpha = f.real(1, "hair alpha");
        return p;
    }
    static float distribution(const spec_fields& f) { return f.size() == 3 ? f.real(2, "layer distribution") : 0.5f; }
};

} // namespace hairshadow
