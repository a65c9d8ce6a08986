// Unreal Engine's hair-count deep shadows (ue:K): the layers' depths and the count's transmittance
// behind sheets of strands at known depths, worked by hand; the "- 1" against the count from zero;
// specs; and the builds every method shares (tiled against buffered, any thread count, the registry).
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace hairshadow;

TEST_CASE("power_layers place Unreal's boundaries: (k / (K + 1))^(1 + 5.2 distribution) of the hair's depth", "[methods][ue]") {
    const power_layers<4> unreal; // LayerDistribution 0.5: exponent 3.6
    CHECK(unreal.fraction(0) == 0.0f);
    CHECK(unreal.fraction(1) == Approx(std::pow(0.2, 3.6)).epsilon(1e-6)); // 0.0030
    CHECK(unreal.fraction(2) == Approx(std::pow(0.4, 3.6)).epsilon(1e-6)); // 0.0369
    CHECK(unreal.fraction(3) == Approx(std::pow(0.6, 3.6)).epsilon(1e-6)); // 0.159
    CHECK(unreal.fraction(4) == Approx(std::pow(0.8, 3.6)).epsilon(1e-6)); // 0.448
    const power_layers<4> even(0.0f); // exponent 1: k / 5
    CHECK(even.fraction(2) == Approx(0.4f));
    CHECK(power_layers<4>(1.0f).fraction(4) == Approx(std::pow(0.8, 6.2)).epsilon(1e-6));
    CHECK_THROWS_AS(power_layers<4>(1.5f), argument_error);
    CHECK_THROWS_AS(power_layers<4>(std::nanf("")), argument_error);

    // A texel whose first fragment is at 0.2, the map 1 deep: a fragment starts adding at the first
    // boundary it is not in front of; behind the last it adds to none.
    power_layers<4> p;
    p.prepare({0.0f, 1.0f});
    const power_layers<4>::texel_state s{0.2f};
    CHECK(p.assign(s, 0.2f) == 0);
    CHECK(p.assign(s, 0.2f + 0.5f * p.fraction(1)) == 0);
    CHECK(p.assign(s, 0.2f + 1.01f * p.fraction(1)) == 1);
    CHECK(p.assign(s, 0.2f + 1.01f * p.fraction(3)) == 3);
    CHECK(p.assign(s, 0.2f + 1.01f * p.fraction(4)) == -1);
    // Queries: in front of z0 nothing; behind, moved back by 0.05 of the first boundary.
    CHECK(p.locate(s, 0.19f).index == -1);
    CHECK(p.locate(s, 0.2f).index == 0);
    CHECK(p.locate(s, 0.2f).fraction == 0.0f);
    CHECK(p.locate(s, 0.2f + 0.05f * p.fraction(1)).fraction == 0.0f); // the bias exactly
    const auto mid = p.locate(s, 0.2f + 0.05f * p.fraction(1) + 0.5f * (p.fraction(2) + p.fraction(3)));
    CHECK(mid.index == 2);
    CHECK(mid.fraction == Approx(0.5f).epsilon(1e-4));
    CHECK(p.locate(s, 0.9f).index == 4);
}

TEST_CASE("hair-count deep shadows give Unreal's count and A^max(0, count - 1) behind sheets of strands", "[methods][ue]") {
    // Sheets at z = 0.5, 0.3, 0.1, -0.1, -0.3, every fragment of alpha 0.3 (b = -ln 0.7): the map's
    // depth D spans the five, so the second sheet lies 0.25 D behind the first, between boundaries 3
    // (0.159 D) and 4 (0.448 D), and the last three behind boundary 4, where Unreal counts nothing.
    const auto scene = test::make_sheets(5, 64);
    const float b = -std::log(0.7f);
    hair_count_deep_shadows<4> ue(power_layers<4>(), hair_count({.hair_alpha = 0.3f}));
    ue.build(scene.model, scene.light, test::alpha(0.3f));
    // Stored: the optical depth in front of each boundary (cumulative): the first sheet in all four,
    // the second in the last.
    CHECK(ue.stored_optical_depth(32, 32, 0) == Approx(b).epsilon(1e-6));
    CHECK(ue.stored_optical_depth(32, 32, 2) == Approx(b).epsilon(1e-6));
    CHECK(ue.stored_optical_depth(32, 32, 3) == Approx(2.0f * b).epsilon(1e-6));

    const depth_extent extent = ue.map_extent();
    const float D = extent.furthest - extent.nearest, z0 = test::depth_at(scene, 0.5f), bias = 0.05f * D * ue.placement().fraction(1);
    // The count at a query depth, by hand: 0 at z0, 1 at boundary 1 (and 2 and 3), 2 at boundary 4,
    // linear between (Unreal's ComputeHairCount); T = 0.7^max(0, count - 1), one hair being alpha 0.3.
    const auto count_at = [&](float z) {
        const float d = std::max(test::depth_at(scene, z) - z0 - bias, 0.0f) / D;
        const auto& p = ue.placement();
        if (d < p.fraction(1)) return d / p.fraction(1);
        if (d < p.fraction(3)) return 1.0f;
        if (d < p.fraction(4)) return 1.0f + (d - p.fraction(3)) / (p.fraction(4) - p.fraction(3));
        return 2.0f;
    };
    const float y = scene.row_y[scene.row_y.size() / 2];
    for (const float z : {0.9f, 0.5f, 0.4999f, 0.45f, 0.3f, 0.2f, 0.1f, -0.9f}) {
        CAPTURE(z, count_at(z));
        const float expected = z > 0.5f ? 1.0f : std::pow(0.7f, std::max(count_at(z) - 1.0f, 0.0f));
        CHECK(ue.transmittance(glm::vec3(0.2f, y, z)) == Approx(expected).epsilon(1e-4));
    }
    // The count passes 1 only beyond boundary 3: everything nearer is lit, the hair's own shadow removed.
    CHECK(ue.transmittance(glm::vec3(0.2f, y, 0.45f)) == 1.0f);
    CHECK(ue.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(0.7f).epsilon(1e-5));

    // Counted from zero, the same maps give interpolation's T: 0.7^count.
    hair_count_deep_shadows<4> zero(power_layers<4>(), hair_count({.hair_alpha = 0.3f, .minus_one = false}));
    zero.build(scene.model, scene.light, test::alpha(0.3f));
    CHECK(zero.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(0.49f).epsilon(1e-5));
    CHECK(zero.transmittance(glm::vec3(0.2f, y, 0.45f)) == Approx(0.7f).epsilon(1e-5));
    // Off the sheets' rows the texels hold no hair: no shadow at any depth.
    CHECK(ue.transmittance(glm::vec3(0.2f, 0.49f, -0.5f)) == 1.0f);
}

TEST_CASE("ue specs parse K, one hair's alpha and the layer distribution, and refuse bad ones", "[methods][ue][spec]") {
    // The method the registry makes, copied out of the map that holds it.
    const auto method = [](const char* text) {
        const auto map = make_shadow_map(text);
        const auto* made = map->method_if<hair_count_deep_shadows<4>>();
        REQUIRE(made != nullptr);
        return *made;
    };
    CHECK(method("ue").reconstruction().parameters() == hair_count_parameters{});
    CHECK(method("ue").placement().distribution() == 0.5f);
    CHECK(method("ue:4:0.2").reconstruction().parameters().hair_alpha == 0.2f);
    CHECK(method("ue:4:0.2:0.25").placement().distribution() == 0.25f);
    CHECK_FALSE(method("ue:4:zero").reconstruction().parameters().minus_one);
    CHECK(make_shadow_map("ue:8")->method_if<hair_count_deep_shadows<8>>() != nullptr);
    CHECK(make_shadow_map("ue:2:8bit")->method_if<hair_count_deep_shadows<2, emulated_8bit>>() != nullptr);
    for (const char* bad : {"ue:", "ue:3", "ue:04", "ue:4:0", "ue:4:1", "ue:4:nan", "ue:4:0.2:2", "ue:4:0.2:-0.1", "ue:4:zero:0.5", "ue:4:0.1:0.5:1",
                            "ue:zero", "ue:4:x"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
}

TEST_CASE("ue maps build tile by tile as from fragments, for any thread count, and through the registry", "[methods][ue][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    CHECK(test::same_maps_tiled_and_buffered(hair_count_deep_shadows<4>(), m, fb, light));
    CHECK(test::same_maps_tiled_and_buffered(hair_count_deep_shadows<8, emulated_8bit>(power_layers<8>(0.2f), hair_count()), m, fb, light));

    // The registry makes the method with the spec's parameters.
    const auto map = make_shadow_map("ue:4:0.2:0.3");
    map->build(m, light);
    hair_count_deep_shadows<4> direct(power_layers<4>(0.3f), hair_count({.hair_alpha = 0.2f}));
    direct.build(m, light);
    CHECK(test::same_transmittance(*map, direct, m));
    CHECK(map->layer_count() == 4);
}
