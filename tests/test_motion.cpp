// Procedural motion (procedural/motion.hpp): sway is deterministic for a seed and any thread count,
// keeps roots and segment lengths, moves the tips; the orbiting light; and a rebuild from the moved
// model, into maps reused frame after frame, equals a fresh build.
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace hairshadow;

namespace {

hair_model small_model() { return make_procedural({.style = hair_style::wavy, .strands = 300, .segments = 24, .seed = 3}); }

float largest_tip_move(const hair_model& a, const hair_model& b) {
    float most = 0.0f;
    for (std::size_t s = 0; s < a.strand_count(); ++s) {
        const std::size_t tip = a.strand_offsets[s + 1] - 1;
        most = std::max(most, glm::length(a.points[tip] - b.points[tip]));
    }
    return most;
}

} // namespace

TEST_CASE("sway is deterministic for a seed and any thread count", "[motion][determinism]") {
    const sway_motion sway(small_model(), {.seed = 7});
    const hair_model one = sway.pose(0.7f, execution{1});
    CHECK(sway.pose(0.7f, execution{1}).points == one.points);
    CHECK(sway.pose(0.7f, execution{3}).points == one.points);
    const sway_motion other(small_model(), {.seed = 8});
    CHECK(other.pose(0.7f).points != one.points);
}

TEST_CASE("sway keeps roots and segment lengths and moves the tips", "[motion]") {
    const hair_model rest = small_model();
    const sway_motion sway(rest, {.amplitude_degrees = 20.0f});
    hair_model posed;
    float most = 0.0f;
    for (float t : {0.0f, 0.31f, 0.9f, 1.7f}) {
        sway.pose(t, posed);
        REQUIRE(posed.strand_offsets == rest.strand_offsets);
        for (std::size_t s = 0; s < rest.strand_count(); ++s) {
            const std::uint32_t first = rest.strand_offsets[s], end = rest.strand_offsets[s + 1];
            CHECK(posed.points[first] == rest.points[first]); // roots stay exactly where they grow
            for (std::uint32_t i = first; i + 1 < end; ++i) {
                const float rest_length = glm::length(rest.points[i + 1] - rest.points[i]);
                CHECK(std::abs(glm::length(posed.points[i + 1] - posed.points[i]) - rest_length) <= 1e-5f * rest_length + 1e-7f);
            }
        }
        most = std::max(most, largest_tip_move(posed, rest));
    }
    // A 0.25 m strand whose tip turns by up to 20 degrees moves by centimetres.
    CHECK(most > 0.02f);
    CHECK(most < 0.25f);
    // Nothing moves without wind.
    const sway_motion still(rest, {.amplitude_degrees = 0.0f});
    CHECK(largest_tip_move(still.pose(1.3f), rest) < 1e-5f);
}

TEST_CASE("sway refuses parameters it cannot use", "[motion][hostile]") {
    const hair_model rest = small_model();
    CHECK_THROWS_AS(sway_motion(rest, {.wind = {0, 1, 0}}), argument_error);
    CHECK_THROWS_AS(sway_motion(rest, {.wind = {0, 0, 0}}), argument_error);
    CHECK_THROWS_AS(sway_motion(rest, {.amplitude_degrees = std::nanf("")}), argument_error);
    CHECK_THROWS_AS(sway_motion(rest, {.period = 0.0f}), argument_error);
    CHECK_THROWS_AS(sway_motion(rest, {.gust_length = -1.0f}), argument_error);
    CHECK_THROWS_AS(sway_motion(rest, {.strand_variation = 2.0f}), argument_error);
    const sway_motion sway(rest);
    CHECK_THROWS_AS(sway.pose(std::numeric_limits<float>::infinity()), argument_error);
    CHECK_THROWS_AS(sway_motion(hair_model{}), model_error);
}

TEST_CASE("an orbiting light turns about the vertical through the centre", "[motion]") {
    const auto sun = light_spec::directional({1, -1, 0});
    CHECK(glm::length(orbit_light(sun, 0.0f, 4.0f).direction - sun.direction) < 1e-6f);
    CHECK(glm::length(orbit_light(sun, 1.0f, 4.0f).direction - glm::vec3(0, -1, -1)) < 1e-5f); // a quarter turn
    CHECK(glm::length(orbit_light(sun, 4.0f, 4.0f).direction - sun.direction) < 1e-5f);
    const auto lamp = light_spec::point({2, 1, 1});
    const auto turned = orbit_light(lamp, 2.0f, 4.0f, {1, 0, 1}); // half a turn about x = 1, z = 1
    CHECK(glm::length(turned.position - glm::vec3(0, 1, 1)) < 1e-5f);
    CHECK_THROWS_AS(orbit_light(sun, 1.0f, 0.0f), argument_error);
}

TEMPLATE_TEST_CASE("maps rebuilt in place from moving hair equal a fresh build", "[motion][tiled]", deep_opacity_maps<3>,
                   (occupancy_maps<128, 4>), opacity_shadow_maps<16>, density_clustering<4>) {
    const sway_motion sway(small_model(), {.amplitude_degrees = 25.0f});
    hair_model moving;
    TestType reused;
    const auto box = sway.rest().bounds();
    for (float t : {0.0f, 0.4f, 0.8f, 1.2f}) {
        sway.pose(t, moving);
        const auto light = light_space::fit(orbit_light(light_spec::directional({0.6f, -1, 0.6f}), t, 3.0f), box.expanded(0.3f), 128);
        reused.build(moving, light);
        TestType fresh;
        fresh.build(sway.pose(t), light);
        for (int y = 0; y < 128; ++y)
            for (int x = 0; x < 128; ++x) REQUIRE(reused.texel(x, y) == fresh.texel(x, y));
        CHECK(reused.fragment_count() == fresh.fragment_count());
        CHECK(reused.fragment_count() > 0);
    }
}
