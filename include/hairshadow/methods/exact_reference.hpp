#pragma once
/// @file
/// The registration of the exact reference, a deep shadow map (Lokovic & Veach 2000), and its
/// compression: the spec `dsm` or `dsm:EPS`. The maps themselves are reference/deep_shadow_map.hpp
/// and reference/compressed_deep_shadow_map.hpp; a family's visit gives exact_reference.

#include <hairshadow/methods/method_family.hpp>

namespace hairshadow {

/// The registration of the exact reference (methods/method_family.hpp).
struct exact_reference_family {
    static constexpr std::string_view name = "dsm";
    static constexpr std::string_view grammar = "dsm (exact) | dsm:EPS (Lokovic-Veach compression, 0 < EPS < 1)";
    static constexpr bool takes_accumulation = false;
    static constexpr auto examples = std::make_tuple(spec_example<exact_reference>{"dsm", in_bench}, spec_example<exact_reference>{"dsm:0.01", in_compare});
    static constexpr std::array<std::string_view, 0> keywords{};

    static void check(const spec_fields& f) {
        if (f.size() > 1) throw f.bad("dsm takes an optional tolerance");
        if (f.size() == 1) {
            const float eps = f.real(0, "tolerance");
            if (!(eps > 0.0f && eps < 1.0f)) throw f.bad("the tolerance must be in (0, 1)");
        }
    }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        visit(exact_reference{f.size() == 1 ? std::optional<float>(f.real(0, "tolerance")) : std::nullopt});
        return true;
    }
};

} // namespace hairshadow
