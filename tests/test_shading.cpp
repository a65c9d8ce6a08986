// Shading and opaque objects on constructed scenes: the mesh under the hair receives the hair's
// transmittance, hair behind the mesh from the light is fully shadowed, lights add; Kajiya-Kay's
// terms and the depth shadow map on their own.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

using namespace hairshadow;

namespace {

/// A square of two triangles at height z, spanning [-half, half] in x and y.
triangle_mesh quad(float z, float half) {
    triangle_mesh m;
    m.vertices = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

camera looking_along_z(float from_z, float to_z, int size) {
    camera c;
    c.eye = {0, 0, from_z};
    c.target = {0, 0, to_z};
    c.up = {0, 1, 0};
    c.width = c.height = size;
    c.near_plane = 0.1f;
    c.far_plane = 20.0f;
    return c;
}

/// The pixel where a world point lands.
std::pair<int, int> pixel_of(const camera& c, const glm::vec3& p) {
    const glm::vec4 clip = c.view_projection() * glm::vec4(p, 1.0f);
    return {int((clip.x / clip.w + 1.0f) * 0.5f * float(c.width)), int((1.0f - clip.y / clip.w) * 0.5f * float(c.height))};
}

} // namespace

TEST_CASE("Kajiya-Kay: diffuse as sin(T, L), specular on the reflection cone", "[shading]") {
    hair_material m;
    m.specular_colour = glm::vec3(0.0f);
    const glm::vec3 t(1, 0, 0);
    CHECK(kajiya_kay(t, {0, 1, 0}, {0, 0, 1}, m).x == Approx(m.colour.x));          // across the strand: full
    CHECK(kajiya_kay(t, {1, 0, 0}, {0, 0, 1}, m).x == Approx(0.0f).margin(1e-6)); // along it: none
    CHECK(kajiya_kay(t, glm::normalize(glm::vec3(1, 1, 0)), {0, 0, 1}, m).x == Approx(m.colour.x * std::sqrt(0.5f)));
    hair_material shiny;
    shiny.colour = glm::vec3(0.0f);
    shiny.specular_colour = glm::vec3(1.0f);
    const glm::vec3 l = glm::normalize(glm::vec3(1, 1, 0));
    CHECK(kajiya_kay(t, l, glm::normalize(glm::vec3(-1, 1, 0)), shiny).x == Approx(1.0f)); // the mirror direction
    CHECK(kajiya_kay(t, l, glm::normalize(glm::vec3(-1, 0, 1)), shiny).x == Approx(1.0f)); // anywhere on the cone
    CHECK(kajiya_kay(t, l, glm::normalize(glm::vec3(1, 1, 0)), shiny).x < 1e-6f);          // back towards the light
}

TEST_CASE("the depth shadow map hides what lies behind the mesh from the light", "[shading]") {
    const auto mesh = quad(0.0f, 1.0f);
    aabb box = mesh.bounds();
    box.add({0, 0, 1});
    box.add({0, 0, -1});
    const auto light = light_space::fit(light_spec::directional({0, 0, -1}), box, 64);
    const depth_shadow_map map(mesh, light);
    CHECK(map.visibility({0.3f, -0.2f, 0.5f}) == 1.0f);   // above: lit
    CHECK(map.visibility({0.3f, -0.2f, 0.0f}) == 1.0f);   // on it: lit (bias)
    CHECK(map.visibility({0.3f, -0.2f, -0.5f}) == 0.0f);  // below: shadowed
    CHECK(map.visibility({1.5f, 0.0f, -0.5f}) == 1.0f);   // beside it
    const depth_shadow_map empty(triangle_mesh{}, light);
    CHECK(empty.visibility({0, 0, -0.5f}) == 1.0f);
}

TEST_CASE("the mesh under the hair receives the hair's transmittance", "[shading]") {
    auto sheets = test::make_sheets(3, 64);
    scene sc;
    sc.hair = sheets.model;
    sc.mesh = quad(-0.5f, 1.0f);
    sc.lights = {{light_spec::directional({0, 0, -1}), glm::vec3(1.0f)}};
    raster_options ro;
    ro.fixed_alpha = 0.4f;
    const deep_shadow_map exact(rasterize(sc.hair, sheets.light, ro), sheets.light);
    const auto cam = looking_along_z(4.0f, 0.0f, 256);
    render_options options;
    options.draw_hair = false; // it still casts its shadow
    std::vector<lit_light> shadowed{{sc.lights[0], query_of(exact), depth_shadow_map(sc.mesh, sheets.light)}};
    std::vector<lit_light> unshadowed{{sc.lights[0], {}, depth_shadow_map(sc.mesh, sheets.light)}};
    const auto with = render_cpu(sc, cam, shadowed, options), without = render_cpu(sc, cam, unshadowed, options);
    const float ambient = sc.mesh_ambient * sc.mesh_colour.x;
    int under = 0, beside = 0;
    for (float x : {-0.7f, -0.2f, 0.3f, 0.8f})
        for (float y : {-0.9f, -0.75f, -0.3f, 0.0f, 0.3f, 0.75f, 0.9f}) {
            const auto [px, py] = pixel_of(cam, {x, y, -0.5f});
            const float ratio = (with.at(px, py).x - ambient) / (without.at(px, py).x - ambient);
            CAPTURE(x, y, ratio);
            if (std::abs(y) < 0.45f) {
                ++under;
                CHECK(ratio == Approx(0.216f).margin(1e-4)); // (1 - 0.4)^3
            } else {
                ++beside;
                CHECK(ratio == Approx(1.0f).margin(1e-6));
            }
        }
    CHECK(under == 12);
    CHECK(beside == 16);
}

TEST_CASE("hair behind the mesh from the light is fully shadowed", "[shading]") {
    auto sheets = test::make_sheets(1, 64);
    scene sc;
    sc.hair = sheets.model;
    sc.mesh = quad(1.5f, 2.0f); // between the light (from +z) and the hair
    sc.lights = {{light_spec::directional({0, 0, -1}), glm::vec3(1.0f)}};
    const auto cam = looking_along_z(-4.0f, 0.0f, 128); // from below: the hair in front of the mesh
    std::vector<lit_light> blocked{{sc.lights[0], {}, depth_shadow_map(sc.mesh, sheets.light)}};
    std::vector<lit_light> open{{sc.lights[0], {}, depth_shadow_map()}};
    const auto dark = shade_hair_points(sc, cam, blocked), lit = shade_hair_points(sc, cam, open);
    for (std::size_t i = 0; i < dark.size(); ++i) {
        CHECK(dark[i].x == Approx(sc.material.ambient * sc.material.colour.x)); // ambient only
        CHECK(lit[i].x > dark[i].x + 0.1f);
    }
    // In the image too: no hair pixel is brighter than the ambient hair over the mesh's shading.
    const auto image_dark = render_cpu(sc, cam, blocked);
    const auto [px, py] = pixel_of(cam, {0.0f, sheets.row_y[sheets.row_y.size() / 2], sheets.sheet_z[0]});
    CHECK(image_dark.at(px, py).x < sc.material.ambient * sc.material.colour.x + 0.25f * sc.mesh_colour.x);
}

TEST_CASE("two lights add", "[shading]") {
    scene sc;
    sc.hair = make_procedural({.style = hair_style::wavy, .strands = 200, .segments = 10});
    sc.mesh = make_sphere({0, 0, 0}, 0.1f, 16);
    const scene_light a{light_spec::directional({0, -1, -0.3f}), glm::vec3(0.8f, 0.7f, 0.6f)};
    const scene_light b{light_spec::point({0.3f, 0.5f, 0.6f}), glm::vec3(0.3f, 0.4f, 0.9f)};
    const auto make = [&](const scene_light& l) {
        const auto space = light_space::fit(l.spec, sc.bounds(), 128);
        auto map = std::make_shared<occupancy_maps<128, 4>>();
        map->build(rasterize(sc.hair, space), space);
        return lit_light{l, [map](std::span<const glm::vec3> p, std::span<float> out) { map->transmittance(p, out); },
                         depth_shadow_map(sc.mesh, space)};
    };
    const auto cam = camera::framing(sc.bounds(), 30.0f, 15.0f, 96, 96);
    const std::vector<lit_light> none, only_a{make(a)}, only_b{make(b)}, both{make(a), make(b)};
    const auto base = render_cpu(sc, cam, none), ia = render_cpu(sc, cam, only_a), ib = render_cpu(sc, cam, only_b),
               iab = render_cpu(sc, cam, both);
    double worst = 0, lit = 0;
    for (std::size_t i = 0; i < base.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, double(std::abs(iab.pixels[i][c] - (ia.pixels[i][c] + ib.pixels[i][c] - base.pixels[i][c]))));
            lit = std::max(lit, double(ia.pixels[i][c] - base.pixels[i][c]));
        }
    CHECK(lit > 0.2);
    CHECK(worst < 1e-5);
}

TEST_CASE("renders are identical for any thread count", "[shading]") {
    scene sc;
    sc.hair = make_procedural({.style = hair_style::curly, .strands = 300, .segments = 12});
    sc.mesh = make_sphere({0, 0, 0}, 0.1f, 24);
    sc.lights = {{light_spec::directional({0.2f, -1, -0.4f}), glm::vec3(1.0f)}};
    const auto space = light_space::fit(sc.lights[0].spec, sc.bounds(), 128);
    deep_opacity_maps<3> dom;
    dom.build(rasterize(sc.hair, space), space);
    const std::vector<lit_light> lights{{sc.lights[0], query_of(dom), depth_shadow_map(sc.mesh, space)}};
    const auto cam = camera::framing(sc.bounds(), 0.0f, 10.0f, 120, 100);
    render_options one, many;
    one.exec.threads = 1;
    many.exec.threads = 5;
    const auto a = render_cpu(sc, cam, lights, one), b = render_cpu(sc, cam, lights, many);
    CHECK(a.pixels == b.pixels);
    CHECK(mean_absolute_difference(a, image(120, 100, sc.background)) > 0.01); // something was drawn
}

TEST_CASE("a spot light lights its cone only", "[shading]") {
    scene sc;
    sc.hair = make_procedural({.style = hair_style::straight, .strands = 300, .segments = 8});
    const scene_light spot{light_spec::spot({0, 0.6f, 0}, {0, -1, 0}, 10.0f), glm::vec3(1.0f)};
    const lit_light light{spot, {}, {}};
    const std::vector<glm::vec3> points{{0, 0.1f, 0}, {0.3f, -0.1f, 0.3f}};
    const auto v = light_visibility(light, points);
    CHECK(v[0] == 1.0f); // on the axis
    CHECK(v[1] == 0.0f); // 36 degrees off it
}

TEST_CASE("bad images and spheres are refused", "[shading][errors]") {
    aabb box;
    box.add({0, 0, 0});
    box.add({1, 1, 1});
    CHECK_THROWS_AS(camera::framing(box, 0, 0, 0, 10), argument_error);
    CHECK_THROWS_AS(camera::framing(box, 0, 0, 10, HAIRSHADOW_MAX_RESOLUTION + 1), argument_error);
    CHECK_THROWS_AS(camera::framing(aabb{}, 0, 0, 10, 10), argument_error);
    CHECK_THROWS_AS(camera::framing(box, 0, 0, 10, 10, std::nanf("")), argument_error);
    CHECK_THROWS_AS(camera::framing(box, std::nanf(""), 0, 10, 10), argument_error);
    CHECK_THROWS_AS(camera::framing(box, 0, 90, 10, 10), argument_error);
    aabb point;
    point.add({1, 1, 1});
    CHECK_THROWS_AS(camera::framing(point, 0, 0, 10, 10), argument_error); // nothing to see around
    CHECK_THROWS_AS(make_sphere({0, 0, 0}, -1.0f), argument_error);
    CHECK_THROWS_AS(make_sphere({0, 0, 0}, 1.0f, 1), argument_error);
}
