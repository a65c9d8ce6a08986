#pragma once
/// @file
/// Occupancy maps (Sintorn & Assarsson 2009): S one-bit slices in each texel's depth range and B slabs
/// of exact sums. The spec `occ:S:B`.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/reconstruction/occupancy_bitcount.hpp>

namespace hairshadow {

/// Occupancy maps (Sintorn & Assarsson 2009): S one-bit slices in each texel's depth range, B slabs.
template <int S, int B, class Accumulation = float_accumulation>
using occupancy_maps = shadow_method<depth_range<S>, Accumulation, occupancy_bitcount<B>>;

namespace detail {
/// occ's and docc's slices and slabs.
struct occupancy_sizes {
    using slices = size_list<32, 64, 128, 256>;
    using slabs = size_list<1, 2, 4, 8>;
    static void check(const spec_fields& f, std::string_view name) {
        if (f.size() != 2 || !slices::contains(f.whole(0)) || !slabs::contains(f.whole(1)))
            throw f.bad(std::string(name) + " needs S = 32, 64, 128 or 256 slices and B = 1, 2, 4 or 8 slabs");
    }
    /// Calls visit(s, b) with the spec's sizes as integral constants.
    template <class Visit>
    static bool with_sizes(const spec_fields& f, Visit&& visit) {
        bool found = false;
        with_size<slices>(f.whole(0), [&](auto s) { found = with_size<slabs>(f.whole(1), [&](auto b) { visit(s, b); }); });
        return found;
    }
};
} // namespace detail

/// The registration of occupancy maps (methods/method_family.hpp).
struct occupancy_maps_family {
    static constexpr std::string_view name = "occ";
    static constexpr std::string_view grammar = "occ:S:B (S = 32, 64, 128, 256; B = 1, 2, 4, 8)";
    static constexpr bool takes_accumulation = true;
    static constexpr auto examples = std::make_tuple(spec_example<occupancy_maps<128, 4>>{"occ:128:4", in_compare | in_bench | in_figure | in_animate},
                                                     spec_example<occupancy_maps<32, 1, emulated_8bit>>{"occ:32:1:8bit"},
                                                     spec_example<occupancy_maps<256, 8>>{"occ:256:8"});
    static constexpr std::array<std::string_view, 0> keywords{};

    static void check(const spec_fields& f) { detail::occupancy_sizes::check(f, name); }
    template <class Accumulation, class Visit>
    static bool visit(const spec_fields& f, Visit&& visit) {
        return detail::occupancy_sizes::with_sizes(f, [&](auto s, auto b) { visit(occupancy_maps<s(), b(), Accumulation>()); });
    }
};

} // namespace hairshadow
