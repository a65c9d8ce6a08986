// The tiled build's capabilities (policies/capabilities.hpp), stated for every method and hybrid the
// library composes: which builds stream, which walk in any order, which AVX-512 steps each placement
// has. A policy that gains or loses a fast path changes a line here; the bit-for-bit tests
// (test_tiled_build.cpp, test_tile_walk.cpp, test_placement_steps.cpp) check each path's maps.
#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

using namespace hairshadow;

namespace {
/// The capabilities a composition is meant to have; the AVX-512 ones only where the vector paths
/// are compiled (elsewhere every one of them is false).
struct expected {
    bool streams, order_free, assigns_each, texel_steps, from_depths;
};

template <class Method>
void check(const expected& e) {
    using c = detail::capabilities_of<Method>;
    CHECK(c::streams == e.streams);
    CHECK(c::order_free == e.order_free);
    constexpr bool vector = HAIRSHADOW_AVX512_WALK;
    CHECK(c::assigns_each == (vector && e.assigns_each));
    CHECK(c::prepares_texel == (vector && e.texel_steps));
    CHECK(c::assigns_texel == (vector && e.texel_steps));
    CHECK(c::counts_texel == (vector && e.texel_steps));
    CHECK(c::from_depths == (vector && e.from_depths));
}
} // namespace

TEST_CASE("every composition of the library has the capabilities its policies declare", "[capabilities]") {
    // The interpolated methods and the occupancy maps stream; density clustering reads a texel's
    // fragments together (k-means), so groups them, and has the vector texel steps instead.
    check<opacity_shadow_maps<16>>({true, true, true, false, false});
    check<opacity_shadow_maps<64, gamma_spacing, emulated_8bit>>({true, true, true, false, false});
    check<deep_opacity_maps<3>>({true, true, true, false, false});
    check<deep_opacity_maps<3, emulated_8bit>>({true, true, true, false, false});
    check<occupancy_maps<128, 4>>({true, true, true, false, false});
    check<deep_occupancy_maps<64, 2>>({true, true, true, false, false});
    check<range_opacity_maps<16>>({true, true, true, false, false});
    check<density_clustering<4>>({false, true, false, true, true});
    check<density_clustering<3, emulated_8bit>>({false, true, false, true, true});
    // A fibre density reads the first fragment (and, measured, the last): no streamed pieces, and it
    // does not say its maps are order free.
    check<approximate_deep_shadow_maps>({false, false, true, false, false});
    check<measured_density_shadow_maps>({false, false, true, false, false});
}

TEST_CASE("the capabilities are the policies' own: each policy alone", "[capabilities]") {
    STATIC_REQUIRE(detail::order_free_maps<per_pixel_depth<3>, interpolation>);
    STATIC_REQUIRE(detail::order_free_maps<clustered<4>, interpolation>); // k-means sums integers
    STATIC_REQUIRE_FALSE(detail::order_free_maps<per_pixel_depth<3>, fibre_density<fibre_density_source::measured>>);
    STATIC_REQUIRE_FALSE(detail::streams_tiles<clustered<4>, float_accumulation, interpolation>);
    STATIC_REQUIRE_FALSE(detail::streams_tiles<per_pixel_depth<1>, float_accumulation, fibre_density<fibre_density_source::fixed>>);
    STATIC_REQUIRE(detail::streams_tiles<per_pixel_depth<128>, emulated_8bit, occupancy_bitcount<1>>);
    // A placement with only the required members: a whole method, built by the grouped build.
    STATIC_REQUIRE_FALSE(detail::assigns_each_avx512<clustered<4>>);
}
