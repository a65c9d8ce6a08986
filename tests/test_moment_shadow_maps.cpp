// Moment shadow maps (msm): the moments behind sheets of strands at known depths, worked by hand; two
// sheets, which four moments determine, give exactly one sheet's shadow between them for any
// overestimation; the bounds (overestimation 0 below the exact optical depth, 1 above it) behind five
// sheets and on Sintel against the exact map; specs; and the builds every method shares.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace hairshadow;

namespace {

raster_options alpha(float a) {
    raster_options o;
    o.fixed_alpha = a;
    return o;
}

moment_shadow_maps with_overestimation(float overestimation) { return moment_shadow_maps{depth_range<1>(), power_moments({.overestimation = overestimation})}; }

} // namespace

TEST_CASE("moment shadow maps store the optical depth and its power moments behind sheets of strands", "[methods][msm]") {
    // Five sheets of alpha 0.3 at z = 0.5 .. -0.3: in each texel's range at z = -1, -0.5, 0, 0.5, 1.
    const auto scene = test::make_sheets(5, 64);
    const double b = -std::log(0.7);
    moment_shadow_maps msm;
    msm.build(scene.model, scene.light, alpha(0.3f));
    CHECK(msm.stored_optical_depth(32, 32, 0) == Approx(5 * b).epsilon(1e-6));
    CHECK(msm.stored_optical_depth(32, 32, 1) == Approx(0.0).margin(1e-5));
    CHECK(msm.stored_optical_depth(32, 32, 2) == Approx(2.5 * b).epsilon(1e-5));  // 1 + 1/4 + 0 + 1/4 + 1
    CHECK(msm.stored_optical_depth(32, 32, 3) == Approx(0.0).margin(1e-5));
    CHECK(msm.stored_optical_depth(32, 32, 4) == Approx(2.125 * b).epsilon(1e-5)); // 1 + 1/16 + 0 + 1/16 + 1
    const float y = scene.row_y[scene.row_y.size() / 2];
    CHECK(msm.transmittance(glm::vec3(0.2f, y, 0.9f)) == 1.0f);
    CHECK(msm.transmittance(glm::vec3(0.2f, y, 0.5f)) == 1.0f);
    CHECK(msm.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(std::pow(0.7, 5)).epsilon(1e-5));
}

TEST_CASE("two sheets, which four moments determine, give one sheet's shadow between them", "[methods][msm]") {
    const auto scene = test::make_sheets(2, 64);
    const float y = scene.row_y[scene.row_y.size() / 2];
    for (const float overestimation : {0.0f, 0.25f, 1.0f}) {
        auto msm = with_overestimation(overestimation);
        msm.build(scene.model, scene.light, alpha(0.3f));
        for (const float z : {0.49f, 0.45f, 0.4f, 0.35f, 0.31f}) {
            CAPTURE(overestimation, z);
            CHECK(msm.transmittance(glm::vec3(0.2f, y, z)) == Approx(0.7f).epsilon(1e-3));
        }
        CHECK(msm.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(0.49f).epsilon(1e-5));
    }
}

TEST_CASE("the moment bound: overestimation 0 never above the exact optical depth, 1 never below it", "[methods][msm]") {
    const auto check_bounds = [](const hair_model& model, const light_space& light, const raster_options& options, std::size_t queries_at_least) {
        const auto fragments = rasterize(model, light, options);
        const deep_shadow_map exact(fragments, light);
        auto lower = with_overestimation(0.0f), upper = with_overestimation(1.0f);
        lower.build(model, light, options);
        upper.build(model, light, options);
        std::size_t queries = 0, below = 0, above = 0;
        double worst_low = 0, worst_high = 0;
        for (int y = 0; y < light.resolution(); ++y)
            for (int x = 0; x < light.resolution(); ++x)
                for (const auto& f : fragments.texel(x, y)) {
                    // Just behind each fragment, where the exact map counts it: the upper bound's
                    // point at the query then holds no fragment of its own.
                    const float depth = std::nextafter(f.depth, 2.0f);
                    const float tau = exact.optical_depth(x, y, depth);
                    const float low = lower.optical_depth(x, y, depth), high = upper.optical_depth(x, y, depth);
                    const float total = lower.stored_optical_depth(x, y, 0);
                    ++queries;
                    worst_low = std::max(worst_low, double(low - tau) / total);
                    worst_high = std::max(worst_high, double(tau - high) / total);
                    below += low <= tau + 1e-3f * total;
                    above += high >= tau - 1e-3f * total;
                }
        CAPTURE(queries, worst_low, worst_high);
        CHECK(queries >= queries_at_least);
        CHECK(below == queries);
        CHECK(above == queries);
    };
    SECTION("five sheets") {
        const auto scene = test::make_sheets(5, 64);
        check_bounds(scene.model, scene.light, alpha(0.3f), 1000);
    }
    SECTION("Sintel, 128x128") {
        const auto m = read_tfx(test::sintel_hair());
        check_bounds(m, light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 128), {}, 100000);
    }
}

TEST_CASE("msm specs parse the overestimation, and refuse bad ones", "[methods][msm][spec]") {
    const auto map = make_shadow_map("msm:4:0");
    const auto* made = map->method_if<moment_shadow_maps>();
    REQUIRE(made != nullptr);
    CHECK(made->reconstruction().parameters().overestimation == 0.0f);
    CHECK(make_shadow_map("msm")->method_if<moment_shadow_maps>()->reconstruction().parameters() == power_moments_parameters{});
    // No bias, or too little: a texel of two depths would leave the moments' matrix singular.
    CHECK_THROWS_AS(power_moments({.bias = 0.0f}), argument_error);
    CHECK_THROWS_AS(power_moments({.bias = 1e-9f}), argument_error);
    CHECK_THROWS_AS(power_moments({.overestimation = std::nanf("")}), argument_error);
    for (const char* bad : {"msm:", "msm:6", "msm:04", "msm:4:1.5", "msm:4:-0.1", "msm:4:nan", "msm:4:0:1", "msm:4:8bit", "msm:x"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
}

TEST_CASE("msm maps build tile by tile as from fragments, for any thread count, and through the registry", "[methods][msm][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    CHECK(test::same_maps_tiled_and_buffered(moment_shadow_maps(), m, fb, light));

    const auto map = make_shadow_map("msm:4:0.5");
    map->build(m, light);
    auto direct = with_overestimation(0.5f);
    direct.build(m, light);
    CHECK(test::same_transmittance(*map, direct, m));
}
