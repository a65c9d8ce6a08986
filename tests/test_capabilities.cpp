// The tiled build's capabilities (policies/capabilities.hpp), stated for every method and hybrid the
// library composes: which builds stream, which walk in any order, which AVX-512 steps each placement
// has. A policy that gains or loses a fast path changes a line here; the bit-for-bit tests
// (test_tiled_build.cpp, test_tile_walk.cpp, test_placement_steps.cpp) check each path's maps.
#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <span>
#include <string_view>

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

namespace {
/// A placement with only the required members (docs/policies.md, "Placement"): four fixed slices
/// of the light's depth, [0, 1/4), [1/4, 1/2), ... No capability, no global state, no contiguity.
struct four_fixed_slices {
    static constexpr int layer_count = 4;
    static constexpr bool cumulative = true;
    static constexpr std::string_view glsl_name = "none";
    struct texel_state {
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };
    void prepare(const depth_extent&) noexcept {}
    template <class Fragment>
    void prepare_texel(std::span<const Fragment>, texel_state&) const noexcept {}
    int assign(const texel_state&, float depth) const noexcept { return std::clamp(int(depth * 4.0f), 0, 3); }
    layer_position locate(const texel_state&, float depth) const noexcept {
        if (!(depth >= 0.0f)) return {-1, 0.0f};
        if (depth >= 1.0f) return {4, 0.0f};
        const int k = std::clamp(int(depth * 4.0f), 0, 3);
        return detail::position_in(k, depth, 0.25f * float(k), 0.25f * float(k + 1));
    }
};
} // namespace

TEST_CASE("a placement with only the required members is a whole method: the tiled build groups it and gives the buffer build's maps", "[capabilities]") {
    using minimal = shadow_method<four_fixed_slices, float_accumulation, interpolation>;
    using c = detail::capabilities_of<minimal>;
    STATIC_REQUIRE_FALSE(c::streams);
    STATIC_REQUIRE_FALSE(c::order_free);
    STATIC_REQUIRE_FALSE(c::assigns_each);
    STATIC_REQUIRE(placement_global_bytes<four_fixed_slices>() == 0);
    STATIC_REQUIRE_FALSE(contiguous_layers<four_fixed_slices>());
    const hair_model model = make_procedural({.style = hair_style::wavy, .strands = 400, .segments = 16, .seed = 3});
    const auto light = light_space::fit(light_spec::directional({0, -1, 0}), model.bounds(), 64);
    minimal tiled, from_buffer;
    tiled.build(model, light);
    from_buffer.build(rasterize(model, light), light, tiled.map_extent());
    std::size_t differing = 0, shadowed = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            differing += !(tiled.texel(x, y) == from_buffer.texel(x, y));
            shadowed += tiled.transmittance(x, y, 1.0f) < 1.0f;
        }
    CHECK(differing == 0);
    CHECK(shadowed > 100);
    CHECK(tiled.memory_bytes() == 64u * 64u * sizeof(minimal::texel_maps));
}
