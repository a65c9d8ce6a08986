// The transmittance-curve error (reference/transmittance_curve_error.hpp) against a hand-computed
// answer: two sheets of strands, one opacity map between them.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace hairshadow;

TEST_CASE("the curve error of one opacity map across two sheets is a^2 / 2b", "[methods][curve]") {
    // Two sheets of alpha a: inside each texel's span the exact T is 1 - a = e^-b. One opacity map
    // spans the same two sheets (D_0 and D_N are the map's extent), so its optical depth rises
    // linearly from 0 to 2b: T(t) = e^(-2bt) for t in [0, 1]. The mean of |e^(-2bt) - e^-b| over
    // [0, 1] is (1 - e^-b)^2 / (2b) = a^2 / (2b).
    const auto scene = test::make_sheets(2, 64);
    raster_options o;
    o.fixed_alpha = 0.4f;
    const auto fragments = rasterize(scene.model, scene.light, o);
    const deep_shadow_map exact(fragments, scene.light);
    opacity_shadow_maps<1> one;
    one.build(fragments, scene.light);
    const double a = 0.4, b = -std::log(1.0 - a);
    CHECK(transmittance_curve_error(one, exact, fragments) == Approx(a * a / (2.0 * b)).epsilon(2e-3));
    // A texel with one fragment has no span and is left out; an empty map has no texel to average.
    CHECK(transmittance_curve_error(one, exact, fragment_buffer()) == 0.0);
    CHECK_THROWS_AS(transmittance_curve_error(one, exact, fragments, 0), argument_error);
}

TEST_CASE("the curve error falls as opacity maps get more slices, and does not depend on threads", "[methods][curve]") {
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 128);
    const auto fragments = rasterize(model, light);
    const deep_shadow_map exact(fragments, light);
    opacity_shadow_maps<16> osm16;
    opacity_shadow_maps<256> osm256;
    osm16.build(fragments, light);
    osm256.build(fragments, light);
    const double e16 = transmittance_curve_error(osm16, exact, fragments, 64, execution{1});
    CHECK(transmittance_curve_error(osm16, exact, fragments, 64, execution{3}) == e16);
    CHECK(transmittance_curve_error(osm256, exact, fragments) < 0.5 * e16);
    CHECK(e16 > 0.0);
}
