#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace hairshadow;

namespace {
aabb unit_box() {
    aabb b;
    b.add({-1, -1, -1});
    b.add({1, 1, 1});
    return b;
}
} // namespace

TEST_CASE("a directional light's frustum holds the whole model with square texels", "[light]") {
    const auto model = make_procedural({.style = hair_style::curly, .strands = 500, .segments = 20});
    for (const auto& dir : {glm::vec3(0, -1, 0), glm::vec3(1, -1, -1), glm::vec3(0, 0, 1)}) {
        const auto ls = light_space::fit(light_spec::directional(dir), model.bounds(), 256);
        for (const auto& p : model.points) {
            const auto td = ls.locate(p);
            REQUIRE(td);
            CHECK(td->depth > 0.0f);
            CHECK(td->depth < 1.0f);
        }
    }
}

TEST_CASE("depth grows along the light direction and texels map back to world sizes", "[light]") {
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), unit_box(), 100);
    const auto front = ls.project({0, 0, 1}), back = ls.project({0, 0, -1});
    CHECK(front.depth < back.depth);
    CHECK(back.depth - front.depth == Approx(2.0f / (ls.far_plane() - ls.near_plane())));
    // One world unit across is res / (2 * 1.01 half-extent) texels.
    const auto left = ls.project({-0.5f, 0, 0}), right = ls.project({0.5f, 0, 0});
    CHECK(right.window.x - left.window.x == Approx(1.0f / ls.texel_size(0.5f)).epsilon(1e-4));
    CHECK(ls.texel_size(0.0f) == ls.texel_size(1.0f));
    CHECK_FALSE(ls.locate({5, 0, 0}));
}

TEST_CASE("a point light sees the model in perspective", "[light]") {
    const auto ls = light_space::fit(light_spec::point({0, 0, 10}), unit_box(), 128);
    CHECK(ls.perspective());
    CHECK(ls.texel_size(1.0f) > ls.texel_size(0.0f)); // footprints grow with distance
    const auto near_pt = ls.project({0, 0, 1}), far_pt = ls.project({0, 0, -1});
    CHECK(near_pt.depth < far_pt.depth);
    CHECK(near_pt.window.x == Approx(64.0f));
    for (int c = 0; c < 8; ++c) CHECK(ls.locate({(c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1}));
    const auto spot = light_space::fit(light_spec::spot({0, 0, 10}, {0, 0, -1}, 20.0f), unit_box(), 128);
    CHECK(spot.locate({0, 0, 0}));
}

TEST_CASE("bad lights and resolutions raise argument_error", "[light][errors]") {
    const auto box = unit_box();
    CHECK_THROWS_WITH(light_space::fit(light_spec::directional({0, 0, 0}), box, 64), Catch::Contains("zero"));
    CHECK_THROWS_AS(light_space::fit(light_spec::directional({std::numeric_limits<float>::quiet_NaN(), 0, 1}), box, 64), argument_error);
    CHECK_THROWS_WITH(light_space::fit(light_spec::directional({0, 0, 1}), box, 0), Catch::Contains("resolution 0"));
    CHECK_THROWS_AS(light_space::fit(light_spec::directional({0, 0, 1}), box, 16385), argument_error);
    CHECK_NOTHROW(light_space::fit(light_spec::directional({0, 0, 1}), box, 16384));
    CHECK_THROWS_WITH(light_space::fit(light_spec::point({0, 0, 0.5f}), box, 64), Catch::Contains("inside"));
    CHECK_THROWS_AS(light_space::fit(light_spec::spot({0, 0, 10}, {0, 0, -1}, 95.0f), box, 64), argument_error);
}

TEST_CASE("light specs parse and reject bad grammar", "[light][errors]") {
    const auto d = parse_light_spec("dir:1,-2,3.5");
    CHECK(d.type == light_type::directional);
    CHECK(d.direction == glm::vec3(1, -2, 3.5f));
    CHECK(parse_light_spec("point:0,5,0").type == light_type::point);
    const auto s = parse_light_spec("spot:0,5,0:0,-1,0:25");
    CHECK(s.spot_half_angle_degrees == 25.0f);
    for (const char* bad : {"dir", "dir:1,2", "dir:a,b,c", "sun:0,1,0", "point:1,2,3:4", "dir:1,2,inf"})
        CHECK_THROWS_AS(parse_light_spec(bad), argument_error);
}

TEST_CASE("a light's parts make the same light again, and any change makes another", "[light]") {
    for (const light_spec& spec : {light_spec::directional({0, -1, -1}), light_spec::point({0, 4, 3}), light_spec::spot({0, 4, 3}, {0, -1, -0.5f}, 40.0f)}) {
        const auto light = light_space::fit(spec, unit_box(), 96);
        const auto again = light_space::from_parts(light.parts());
        CHECK(again.parts() == light.parts());
        const auto a = again.project({0.3f, -0.2f, 0.1f}), b = light.project({0.3f, -0.2f, 0.1f});
        CHECK((a.window == b.window && a.depth == b.depth && a.w == b.w)); // bit for bit
        auto p = light.parts();
        p.near_plane = std::nextafter(p.near_plane, -1.0f);
        CHECK_FALSE(p == light.parts());
        p = light.parts();
        p.view[3][1] += 1e-3f;
        CHECK_FALSE(p == light.parts());
        p.view[3][1] = std::numeric_limits<float>::quiet_NaN();
        CHECK_THROWS_AS(light_space::from_parts(p), argument_error);
        p = light.parts();
        p.far_plane = p.near_plane;
        CHECK_THROWS_AS(light_space::from_parts(p), argument_error);
        p = light.parts();
        p.resolution = 0;
        CHECK_THROWS_AS(light_space::from_parts(p), argument_error);
    }
}
