// The tiled build (methods/detail/tiled_build.hpp): the maps of the fragment-buffer build, bit for bit, for
// every published method and hybrid, any thread count and tile size; where it walks in any order and
// builds without grouping fragments.
#include "tiled_build_support.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <numeric>
#include <random>
#include <set>
#include <thread>
#include <tuple>

using namespace hairshadow;
using namespace test;

TEMPLATE_TEST_CASE("the tiled build gives the fragment-buffer build's maps, bit for bit", "[tiled][determinism]", opacity_shadow_maps<16>,
                   (opacity_shadow_maps<16, gamma_spacing>), deep_opacity_maps<3>, density_clustering<4>, (occupancy_maps<128, 4>),
                   deep_opacity_maps_8bit<3>, (deep_occupancy_maps<128, 4>), range_opacity_maps<16>,
                   (shadow_method<per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::ignore>, float_accumulation, interpolation>),
                   (opacity_shadow_maps<64, uniform_spacing, emulated_8bit>), (opacity_shadow_maps<37, gamma_spacing>),
                   (shadow_method<uniform_slices<64>, float_accumulation, occupancy_bitcount<2>>), (occupancy_maps<32, 1, emulated_8bit>),
                   (shadow_method<depth_range<24>, float_accumulation, interpolation>),
                   (shadow_method<per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation, interpolation>),
                   (density_clustering<3, emulated_8bit>)) {
    const std::string name = GENERATE("sintel", "curly");
    CAPTURE(name);
    const auto& model = test_model(name);
    const auto light = light_space::fit(light_spec::directional({0.3f, -1, -0.5f}), model.bounds(), name == "sintel" ? 512 : 256);
    check_tiled_equals_buffer<TestType>(model, light);
}

TEST_CASE("the tiled build gives the fragment-buffer build's maps on the 1.5M-segment curly model", "[tiled][dense]") {
    // The benchmark's model at 128x128: its 12.26 M fragments at 512x512 (98 a covered texel, at most
    // 292) become 3.06 M in 7,914 texels, 387 a texel and up to 1,025, past the 1,024 sums that
    // interpolation keeps per thread for a texel of one optical depth (accumulation/detail/repeated_sums.hpp).
    const hair_model curly = make_procedural({.style = hair_style::curly, .strands = 10000, .segments = 150, .seed = 1});
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), curly.bounds(), 128);
    check_tiled_equals_buffer<deep_opacity_maps<3>>(curly, light);
    check_tiled_equals_buffer<occupancy_maps<128, 4>>(curly, light);
    check_tiled_equals_buffer<opacity_shadow_maps<16>>(curly, light);
    check_tiled_equals_buffer<density_clustering<4>>(curly, light);
}

TEST_CASE("the tiled build matches on the scalar paths: perspective lights, per-point attributes, fixed alpha, wide lines", "[tiled]") {
    const auto& sintel = test_model("sintel");
    SECTION("a point light (coverage weighted by depth)") {
        const auto light = light_space::fit(light_spec::point({0.4f, 2.2f, 0.6f}), sintel.bounds(), 256);
        check_tiled_equals_buffer<deep_opacity_maps<3>>(sintel, light);
        check_tiled_equals_buffer<occupancy_maps<128, 4>>(sintel, light);
    }
    SECTION("a spot light without depth weighting: one alpha, perspective interpolation") {
        const auto light = light_space::fit(light_spec::spot({0.0f, 2.2f, 0.0f}, {0, -1, 0}, 20.0f), sintel.bounds(), 256);
        check_tiled_equals_buffer<deep_opacity_maps<3>>(sintel, light, {.depth_weighting = false});
    }
    SECTION("per-point thickness and transparency") {
        hair_model m = make_procedural({.style = hair_style::wavy, .strands = 600, .segments = 24, .seed = 5});
        m.thickness.resize(m.point_count());
        m.transparency.resize(m.point_count());
        for (std::size_t i = 0; i < m.point_count(); ++i) {
            m.thickness[i] = 0.0004f + 0.0003f * float(i % 7);
            m.transparency[i] = 0.1f * float(i % 5);
        }
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), 200);
        check_tiled_equals_buffer<density_clustering<4>>(m, light);
        check_tiled_equals_buffer<opacity_shadow_maps<8>>(m, light);
    }
    SECTION("a fixed alpha and pre-filtered wide lines") {
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), sintel.bounds(), 256);
        check_tiled_equals_buffer<deep_opacity_maps<3>>(sintel, light, {.fixed_alpha = 0.3f});
        check_tiled_equals_buffer<occupancy_maps<128, 4>>(sintel, light, {.wide = 3.0f});
    }
}

TEST_CASE("maps that see part of the model, and segments clipped at the near plane, come out the same for every tile size", "[tiled]") {
    // A spot light inside the hair: segments behind it, crossing its near plane, and leaving its map.
    const auto& sintel = test_model("sintel");
    const auto centre = sintel.bounds().center();
    const auto light = light_space::fit(light_spec::spot(centre + glm::vec3(0.0f, 0.05f, 0.0f), {0.2f, -1.0f, 0.1f}, 35.0f), sintel.bounds(), 300);
    raster_options scalar;
    scalar.instructions = instruction_set::scalar;
    scalar.tile_size = 16;
    opacity_shadow_maps<16> reference;
    reference.build(sintel, light, scalar);
    CHECK(reference.fragment_count() > 10000);
    for (const int tile : {8, 24, 64, 128, 301}) {
        CAPTURE(tile);
        raster_options o;
        o.tile_size = tile;
        opacity_shadow_maps<16> osm;
        osm.build(sintel, light, o);
        CHECK(osm.map_extent().nearest == reference.map_extent().nearest);
        CHECK(osm.map_extent().furthest == reference.map_extent().furthest);
        CHECK(osm.fragment_count() == reference.fragment_count());
        CHECK(same_maps(osm, reference));
    }
    check_tiled_equals_buffer<occupancy_maps<128, 4>>(sintel, light);
}

TEST_CASE("the whole-map extent from the segments holds every fragment, and is close to the fragments' own", "[tiled][extent]") {
    const std::string name = GENERATE("sintel", "curly");
    CAPTURE(name);
    const auto& model = test_model(name);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 512);
    const fragment_buffer fragments = rasterize(model, light);
    const depth_extent exact = extent_of(fragments);
    deep_opacity_maps<3> dom;
    dom.build(model, light);
    const depth_extent from_segments = dom.map_extent();
    CHECK(from_segments.nearest <= exact.nearest);
    CHECK(from_segments.furthest >= exact.furthest);
    const float half_range_segments = 0.5f * (from_segments.furthest - from_segments.nearest), half_range_fragments = 0.5f * (exact.furthest - exact.nearest);
    WARN(name << ": DOM's default extent (half the depth range) " << half_range_segments << " from the segments, " << half_range_fragments
              << " from the fragments; nearest " << from_segments.nearest << " vs " << exact.nearest << ", furthest " << from_segments.furthest
              << " vs " << exact.furthest);
    CHECK(half_range_segments == Approx(half_range_fragments).epsilon(0.02));
    CHECK(dom.placement().extent() == Approx(std::max(half_range_segments, 1e-6f)));
    // OSM places its slices with the same extent.
    opacity_shadow_maps<16> osm;
    osm.build(model, light);
    CHECK(osm.placement().nearest() == from_segments.nearest);
    // An empty map: the same {0, 0} as an empty buffer.
    const auto elsewhere = light_space::fit(light_spec::directional({0, -1, -1}), aabb{glm::vec3(5.0f), glm::vec3(6.0f)}, 64);
    deep_opacity_maps<3> empty;
    empty.build(model, elsewhere);
    CHECK(empty.fragment_count() == 0);
    CHECK(empty.map_extent().nearest == 0.0f);
    CHECK(empty.map_extent().furthest == 0.0f);
}

TEST_CASE("a rebuild reuses its working memory and gives the same maps", "[tiled]") {
    const auto& model = test_model("sintel");
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 512);
    occupancy_maps<128, 4> occ;
    occ.build(model, light);
    const auto first = occ;
    const std::size_t workspace = occ.workspace_bytes();
    CHECK(workspace > 0);
    CHECK(first.workspace_bytes() == 0); // copies carry no working memory
    for (int i = 0; i < 3; ++i) occ.build(model, light);
    CHECK(occ.workspace_bytes() == workspace);
    CHECK(same_maps(occ, first));
    CHECK(count_fragments(model, light) == rasterize(model, light).size());
}

TEMPLATE_TEST_CASE("a map built again from another model, light or size writes every texel", "[tiled]",
                   deep_opacity_maps<3>, density_clustering<4>, (occupancy_maps<128, 4>)) {
    // A rebuild keeps the last build's texels, so every build must write each one, where it has
    // fragments and where not: texels left from Sintel seen from the side would show here.
    const auto& sintel = test_model("sintel");
    const auto& curly = test_model("curly");
    const auto side = light_space::fit(light_spec::directional({1, 0, 0}), sintel.bounds(), 256);
    const struct {
        const hair_model* model;
        light_space light;
    } builds[] = {{&sintel, side},
                  {&curly, light_space::fit(light_spec::directional({0.3f, -1, 0.2f}), curly.bounds(), 128)},  // smaller
                  {&curly, light_space::fit(light_spec::point({0.4f, 2.2f, 0.6f}), curly.bounds(), 320)},      // larger
                  {&sintel, light_space::fit(light_spec::directional({0, -1, -1}), sintel.bounds(), 256)}};
    TestType reused;
    for (const auto& b : builds) {
        CAPTURE(b.light.resolution());
        reused.build(*b.model, b.light);
        TestType fresh;
        fresh.build(*b.model, b.light);
        CHECK(same_maps(reused, fresh));
        // From a fragment buffer, the same.
        TestType from_fragments;
        from_fragments.build(sintel, side);
        from_fragments.build(rasterize(*b.model, b.light), b.light, fresh.map_extent());
        CHECK(same_maps(from_fragments, fresh));
    }
}

TEST_CASE("a build walks in any order only where its maps cannot tell: order-free policies, and no depth of -0", "[tiled]") {
    using dom = per_pixel_depth<3>;
    // Which compositions are order free: tests/test_capabilities.cpp.
    CHECK(detail::walks_in_any_order<dom, interpolation>({0.1f, 0.9f}));
    CHECK(detail::walks_in_any_order<dom, interpolation>({-0.9f, -0.1f}));
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({0.0f, 0.9f}));   // an end at +0 may be -0 beside it
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({-0.2f, 0.9f}));  // ends of both signs: one may be -0
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({-0.9f, -0.0f}));
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({0.0f, 0.0f}));   // nothing reaches the map
    CHECK(detail::walks_in_any_order<clustered<4>, interpolation>({0.1f, 0.9f}));
    CHECK_FALSE(detail::walks_in_any_order<dom, fibre_density<fibre_density_source::measured>>({0.1f, 0.9f}));
}
