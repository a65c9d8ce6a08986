// Approximate deep shadow maps (AMD TressFX) and their measured-density variant: TressFX's formula
// behind sheets of strands at known depths, the exact answer at evenly spaced sheets, specs, and the
// builds every method shares (tiled against buffered, any thread count, the registry).
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace hairshadow;

namespace {

/// Transmittance at world points (x, y, z) for each z, on the sheets' middle row.
template <class Map>
std::vector<float> along_row(const Map& map, const test::sheets_scene& scene, std::initializer_list<float> zs) {
    const float y = scene.row_y[scene.row_y.size() / 2];
    std::vector<float> t;
    for (float z : zs) t.push_back(map.transmittance(glm::vec3(0.2f, y, z)));
    return t;
}

} // namespace

TEST_CASE("approximate deep shadow maps give TressFX's transmittance behind sheets of strands", "[methods][adsm]") {
    const auto scene = test::make_sheets(3, 64); // sheets at z = 0.5, 0.3, 0.1, the light travelling along -z
    // One fibre every 0.5 x 0.2 = 0.1 world units behind the first sheet, each of alpha 0.3.
    approximate_deep_shadow_maps adsm(per_pixel_depth<1>(), fibre_density<>({.spacing = 0.5f, .radius = 0.2f, .alpha = 0.3f}));
    adsm.build(scene.model, scene.light, test::alpha(0.9f)); // the fragments' own alpha plays no part
    // d = 0 (in front of and on the first sheet), 0.05 (raised to one fibre), 0.2, 0.4, 1.0 behind it.
    const auto t = along_row(adsm, scene, {0.9f, 0.5f, 0.45f, 0.3f, 0.1f, -0.5f});
    CHECK(t[0] == 1.0f);
    CHECK(t[1] == 1.0f);
    CHECK(t[2] == Approx(0.7f).epsilon(1e-5));
    CHECK(t[3] == Approx(std::pow(0.7f, 2.0f)).epsilon(1e-4));
    CHECK(t[4] == Approx(std::pow(0.7f, 4.0f)).epsilon(1e-4));
    CHECK(t[5] == Approx(std::pow(0.7f, 10.0f)).epsilon(1e-4));
    // Off the sheets' rows the texels hold no hair: no shadow at any depth.
    CHECK(adsm.transmittance(glm::vec3(0.2f, 0.49f, -0.5f)) == 1.0f);

    // An optional cap on the fibres counted (ours: TressFX's shader counts them all).
    approximate_deep_shadow_maps capped(per_pixel_depth<1>(), fibre_density<>({.spacing = 0.5f, .radius = 0.2f, .alpha = 0.3f, .max_fibres = 5}));
    capped.build(scene.model, scene.light);
    const auto c = along_row(capped, scene, {0.1f, -0.5f});
    CHECK(c[0] == Approx(std::pow(0.7f, 4.0f)).epsilon(1e-4));
    CHECK(c[1] == Approx(std::pow(0.7f, 5.0f)).epsilon(1e-4));

    // By default no cap, as in TressFX: 0.005 world units a fibre, so 1.0 behind the first sheet is 200
    // fibres, four times the 50 that TressFX's settings name (and its shader never reads).
    CHECK(fibre_density_parameters{}.max_fibres == std::numeric_limits<float>::infinity());
    approximate_deep_shadow_maps dense(per_pixel_depth<1>(), fibre_density<>({.spacing = 0.5f, .radius = 0.01f, .alpha = 0.01f}));
    dense.build(scene.model, scene.light);
    CHECK(along_row(dense, scene, {-0.5f})[0] == Approx(std::pow(0.99f, 200.0f)).epsilon(1e-3));
    approximate_deep_shadow_maps dense_capped(per_pixel_depth<1>(), fibre_density<>({.spacing = 0.5f, .radius = 0.01f, .alpha = 0.01f, .max_fibres = 50}));
    dense_capped.build(scene.model, scene.light);
    CHECK(along_row(dense_capped, scene, {-0.5f})[0] == Approx(std::pow(0.99f, 50.0f)).epsilon(1e-3));
}

TEST_CASE("the measured fibre density equals the exact answer at evenly spaced sheets", "[methods][adsm]") {
    const auto scene = test::make_sheets(5, 64); // z = 0.5, 0.3, ..., -0.3
    measured_density_shadow_maps measured;
    measured.build(scene.model, scene.light, test::alpha(0.4f));
    const deep_shadow_map exact(rasterize(scene.model, scene.light, test::alpha(0.4f)), scene.light);
    const auto at_sheets = {0.5f, 0.3f, 0.1f, -0.1f, -0.3f, -0.35f, -0.9f};
    const auto t = along_row(measured, scene, at_sheets), e = along_row(exact, scene, at_sheets);
    for (std::size_t j = 0; j < t.size(); ++j) {
        CAPTURE(j);
        const float expected = std::pow(0.6f, float(std::min<std::size_t>(j, 5))); // j sheets in front; all five behind the last, however near
        CHECK(e[j] == Approx(expected).epsilon(1e-4));
        CHECK(t[j] == Approx(expected).epsilon(1e-4));
    }
    // Between sheets the count rises linearly: halfway from the second to the third, 1.5 fibres.
    CHECK(along_row(measured, scene, {0.2f})[0] == Approx(std::pow(0.6f, 1.5f)).epsilon(1e-4));
    // Just behind the first sheet, one whole fibre (TressFX's rule), as the exact map says.
    CHECK(along_row(measured, scene, {0.49f})[0] == Approx(0.6f).epsilon(1e-4));
    CHECK(measured.stored_optical_depth(32, 32, 0) == Approx(-5.0 * std::log(0.6)).epsilon(1e-5));
}

TEST_CASE("adsm specs parse TressFX's parameters and refuse bad ones", "[methods][adsm][spec]") {
    // The parameters the registry builds with: the method it makes, and its reconstruction's.
    const auto parameters = [](const char* text) {
        auto map = make_shadow_map(text);
        REQUIRE(map->method_if<approximate_deep_shadow_maps>() != nullptr);
        return map->method_if<approximate_deep_shadow_maps>()->reconstruction().parameters();
    };
    CHECK(parse_method_spec("adsm").family == "adsm");
    CHECK(parameters("adsm") == fibre_density_parameters{});
    CHECK(make_shadow_map("adsm:auto")->method_if<measured_density_shadow_maps>() != nullptr);
    CHECK(make_shadow_map("adsm")->method_if<measured_density_shadow_maps>() == nullptr);
    CHECK(parameters("adsm:0.4:0.0021:0.35:8").max_fibres == 8.0f);
    CHECK(std::isinf(parameters("adsm:0.4:0.0021:0.35").max_fibres)); // no cap unless asked
    const auto given = parameters("adsm:0.5:0.002:0.3");
    CHECK(given.spacing == 0.5f);
    CHECK(given.radius == 0.002f);
    CHECK(given.alpha == 0.3f);
    for (const char* bad : {"adsm:", "adsm:automatic", "adsm:auto:1", "adsm:1:1", "adsm:0:1:0.5", "adsm:1:-1:0.5", "adsm:1:1:1", "adsm:1:1:0",
                            "adsm:nan:1:0.5", "adsm:1:inf:0.5", "adsm:1:1:0.5:0.5", "adsm:1:1:0.5:inf", "adsm:1:1:0.5:1.5", "adsm:1:1:0.5:0", "adsm:1:1:0.5:08", "adsm:1:1:0.5:2:3", "adsm:8bit", "adsm:1e30:1e30:0.5", "adsm:x:1:0.5"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
}

TEST_CASE("adsm maps build tile by tile as from fragments, for any thread count, and through the registry", "[methods][adsm][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    CHECK(test::same_maps_tiled_and_buffered(approximate_deep_shadow_maps(), m, fb, light));
    CHECK(test::same_maps_tiled_and_buffered(measured_density_shadow_maps(), m, fb, light));

    // The registry makes the method with the spec's parameters.
    const auto map = make_shadow_map("adsm:0.5:0.01:0.2");
    map->build(m, light);
    approximate_deep_shadow_maps direct(per_pixel_depth<1>(), fibre_density<>({.spacing = 0.5f, .radius = 0.01f, .alpha = 0.2f}));
    direct.build(m, light);
    CHECK(test::same_transmittance(*map, direct, m));
    CHECK(map->stored_maps() == 0);
    CHECK(map->layer_count() == 0); // a depth map, no layers
    CHECK(make_shadow_map("adsm:auto")->layer_count() == 1);
    CHECK(make_shadow_map("adsm:auto")->stored_maps() == 1);
    // z0 and a covered flag; depth range plus the sum and the count.
    CHECK(*map->memory_bytes_at(512) == 512u * 512u * 8u + sizeof(float));
    CHECK(*make_shadow_map("adsm:auto")->memory_bytes_at(512) == 512u * 512u * 16u);
}

TEST_CASE("a point a rounding step behind the first fragment is on it, however deep the light's map", "[methods][adsm]") {
    // A map 10,000 world units deep: one float step of a linear depth near 1 is 6e-4 world units,
    // beyond TressFX's 1e-5, so the threshold must also hold in linear depth.
    aabb box;
    box.add({-1, -1, 0});
    box.add({1, 1, 10000});
    const auto light = light_space::fit(light_spec::directional({0, 0, -1}), box, 8);
    fibre_density<> fibres({.spacing = 1.0f, .radius = 1.0f, .alpha = 0.3f});
    fibres.prepare(light);
    const per_pixel_depth<1> placement;
    using storage = fibre_density<>::storage<per_pixel_depth<1>, float_accumulation>;
    const per_pixel_depth<1>::texel_state state{0.9f};
    const auto od = [&](float depth) { return fibres.optical_depth<per_pixel_depth<1>, float_accumulation>(placement, state, storage{true}, depth); };
    CHECK(od(0.9f) == 0.0f);
    CHECK(od(std::nextafter(0.9f, 1.0f)) == 0.0f);
    CHECK(od(std::nextafter(std::nextafter(0.9f, 1.0f), 1.0f)) == 0.0f);
    CHECK(od(0.9f + 1e-6f) == Approx(-std::log(0.7f))); // well behind: one whole fibre (0.01 world units)
    const float deeper = 0.9f + 1e-3f, units = (deeper - 0.9f) * fibres.depth_scale(); // about 10 world units: 10 fibres
    CHECK(units > 9.0f);
    CHECK(od(deeper) == Approx(-double(units) * std::log(0.7)));
}
