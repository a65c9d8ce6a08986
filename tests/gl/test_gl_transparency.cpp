// Transparent hair on GL (Sintorn & Assarsson 3.4) against the CPU's: the same camera fragments,
// blended by depth peeling, occupancy order and weighted averages.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>
#include <hairshadow/shading/transparency.hpp>

#include "../test_support.hpp"

#include <algorithm>

using namespace hairshadow;

namespace {
/// A lit head of hair over a sphere; the hair casts no shadow, so that both back ends shade each
/// strand point alike and only the blending differs.
struct transparent_scene {
    scene sc;
    std::vector<light_space> spaces;
    std::vector<lit_light> cpu_lights;

    explicit transparent_scene(std::size_t strands) {
        sc.hair = make_procedural({.style = hair_style::wavy, .strands = strands, .segments = 16});
        sc.mesh = make_sphere({0, 0, 0}, 0.1f, 32);
        sc.lights = {{light_spec::directional({-0.6f, -1.0f, -0.4f}), glm::vec3(1.0f)}, {light_spec::point({0.4f, 0.1f, 0.5f}), glm::vec3(0.3f, 0.35f, 0.5f)}};
        for (const auto& light : sc.lights) {
            spaces.push_back(light_space::fit(light.spec, sc.bounds(), 256));
            cpu_lights.push_back({light, {}, depth_shadow_map(sc.mesh, spaces.back())});
        }
    }
    void add_lights(gl::scene_renderer& renderer) const {
        for (std::size_t i = 0; i < sc.lights.size(); ++i) renderer.add_unshadowed_light(sc.lights[i], spaces[i]);
    }
};

double mean_difference_linear(const image& a, const image& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += double(glm::dot(glm::abs(a.pixels[i] - b.pixels[i]), glm::vec3(1.0f / 3.0f)));
    return sum / double(a.pixels.size());
}
} // namespace

TEST_CASE("GL transparent hair blends the CPU's camera fragments", "[gl][transparency]") {
    test::gl_context();
    const transparent_scene s(1500);
    const auto cam = camera::framing(s.sc.bounds(), 20.0f, 10.0f, 128, 128);
    gl::scene_renderer renderer(s.sc);
    s.add_lights(renderer);
    const float opacity = 0.4f;
    std::array<image, 4> on_gl, on_cpu;
    for (auto mode : {transparency::none, transparency::occupancy, transparency::weighted, transparency::exact}) {
        renderer.set_transparency(mode, opacity);
        on_gl[std::size_t(mode)] = renderer.render(cam);
        on_cpu[std::size_t(mode)] = render_transparent(s.sc, cam, s.cpu_lights, mode, opacity);
    }
    const auto& exact = on_gl[std::size_t(transparency::exact)];
    CHECK(mean_difference_linear(exact, image(128, 128, s.sc.background)) > 0.02); // the scene is there

    { // each mode agrees with the CPU's
        for (auto mode : {transparency::occupancy, transparency::weighted, transparency::exact}) {
            const double difference = mean_difference_linear(on_gl[std::size_t(mode)], on_cpu[std::size_t(mode)]);
            CAPTURE(int(mode), difference);
            CHECK(difference < 2e-5);
        }
    }
    { // depth peeling (the last render) takes one layer per distinct depth of the deepest pixel:
      // equal depths (where a strand's segments meet) peel together
        const auto surface = hairshadow::detail::rasterise_mesh(s.sc.mesh, cam, {});
        const auto colours = shade_hair_points(s.sc, cam, s.cpu_lights);
        const auto fragments = collect_camera_fragments(s.sc.hair, colours, cam, surface.inv_w, opacity);
        std::size_t layers = 0, deepest = 0;
        for (std::size_t i = 0; i + 1 < fragments.offsets.size(); ++i) {
            std::vector<float> depths;
            for (const auto& f : fragments.pixel(i)) depths.push_back(f.depth);
            std::sort(depths.begin(), depths.end());
            layers = std::max(layers, std::size_t(std::unique(depths.begin(), depths.end()) - depths.begin()));
            deepest = std::max(deepest, depths.size());
        }
        CAPTURE(layers, deepest, renderer.peeled_layers());
        CHECK(layers > 10);
        CHECK(renderer.peeled_layers() == int(layers));
    }
    { // opaque hair after transparent hair is drawn as before
        renderer.set_transparency(transparency::none);
        CHECK(mean_difference_linear(renderer.render(cam), on_gl[std::size_t(transparency::none)]) == 0.0);
    }
    { // occupancy order is closer to exact blending than weighted averages are
        const double occupancy_error = mean_difference_linear(on_gl[std::size_t(transparency::occupancy)], exact);
        const double weighted_error = mean_difference_linear(on_gl[std::size_t(transparency::weighted)], exact);
        CAPTURE(occupancy_error, weighted_error);
        CHECK(occupancy_error < 0.5 * weighted_error);
        CHECK(weighted_error > 1e-3); // the modes differ here
    }
}

TEST_CASE("GL transparent hair follows the blending equation on uniform strands", "[gl][transparency]") {
    test::gl_context();
    // Unlit hair shows its ambient colour alone: every fragment has the same colour, so a pixel shows
    // colour (1 - T) + background T, T = prod(1 - alpha_i) for exact and occupancy-ordered blending
    // (whose correction restores the exact alpha), (1 - mean alpha)^n for weighted averages.
    scene sc;
    sc.hair = make_procedural({.style = hair_style::straight, .strands = 60, .segments = 4});
    sc.material.ambient = 1.0f;
    sc.material.colour = glm::vec3(0.9f, 0.6f, 0.3f);
    sc.background = glm::vec3(0.1f, 0.2f, 0.4f);
    const auto cam = camera::framing(sc.bounds(), 30.0f, 20.0f, 64, 64);
    gl::scene_renderer renderer(sc);
    const float opacity = 0.5f;
    for (auto mode : {transparency::occupancy, transparency::weighted, transparency::exact}) {
        renderer.set_transparency(mode, opacity);
        const auto out = renderer.render(cam);
        const auto fragments = collect_camera_fragments(sc.hair, std::vector<glm::vec3>(sc.hair.point_count(), sc.material.colour), cam, {}, opacity);
        int checked = 0;
        for (std::size_t i = 0; i < out.pixels.size(); ++i) {
            const auto frags = fragments.pixel(i);
            float through = 1.0f, alpha_sum = 0.0f;
            for (const auto& f : frags) through *= 1.0f - f.alpha, alpha_sum += f.alpha;
            // Weighted averages let the mean alpha through n times instead.
            if (mode == transparency::weighted && !frags.empty()) through = std::pow(1.0f - alpha_sum / float(frags.size()), float(frags.size()));
            const glm::vec3 expected = sc.material.colour * (1.0f - through) + sc.background * through;
            // A fragment of almost no coverage may fall on either side of a line's edge on the two
            // back ends; weighted averages count it as a whole fragment.
            const double margin = mode == transparency::weighted ? 5e-3 : 1e-3;
            for (int c = 0; c < 3; ++c) CHECK(out.pixels[i][c] == Approx(expected[c]).margin(margin));
            checked += frags.size() > 1;
        }
        CAPTURE(int(mode));
        CHECK(checked > 50);
    }
}

TEST_CASE("GL transparent hair refuses bad settings", "[gl][transparency]") {
    test::gl_context();
    const transparent_scene s(50);
    gl::scene_renderer renderer(s.sc);
    CHECK_THROWS_AS(renderer.set_transparency(transparency::exact, 0.0f), argument_error);
    CHECK_THROWS_AS(renderer.set_transparency(transparency::exact, std::nanf("")), argument_error);
    CHECK_THROWS_AS(renderer.set_transparency(transparency::exact, 0.5f, 0.0f), argument_error);
    CHECK(renderer.transparency_mode() == transparency::none);
}

// Depth peeling draws the hair twice per layer, and the whole Sintel hair peels 561 layers at 256x256
// (a minute on llvmpipe): every fourth strand of it at 128x128 keeps the test in the suite.
TEST_CASE("on the Sintel hair GL occupancy-ordered blending is closer to depth peeling than weighted averages", "[gl][transparency][sintel]") {
    test::gl_context();
    scene sc;
    const hair_model sintel = read_tfx(test::sintel_hair());
    for (std::size_t s = 0; s < sintel.strand_count(); s += 4) sc.hair.add_strand(sintel.strand(s));
    sc.hair.default_thickness = sintel.default_thickness;
    REQUIRE((sintel.thickness.empty() && sintel.transparency.empty() && sintel.colors.empty())); // nothing per point to carry over
    sc.lights = {{light_spec::directional({-0.7f, -0.9f, -0.45f}), glm::vec3(1.1f)}};
    const auto space = light_space::fit(sc.lights[0].spec, sc.bounds(), 256);
    const gl::hair_mesh mesh(sc.hair);
    gl::maps<occupancy_maps<128, 4>> shadows;
    shadows.build(mesh, space);
    gl::scene_renderer renderer(sc);
    renderer.add_light(sc.lights[0], shadows);
    const auto cam = camera::framing(sc.bounds(), 25.0f, 10.0f, 128, 128, 1.15f);
    std::vector<image> images;
    int layers = 0;
    for (auto mode : {transparency::exact, transparency::occupancy, transparency::weighted, transparency::none}) {
        renderer.set_transparency(mode, 0.4f);
        images.push_back(renderer.render(cam));
        if (mode == transparency::exact) layers = renderer.peeled_layers();
    }
    CHECK(layers > 50);
    const double occupancy_error = mean_absolute_difference(images[1], images[0]);
    const double weighted_error = mean_absolute_difference(images[2], images[0]);
    const double opaque_error = mean_absolute_difference(images[3], images[0]);
    CAPTURE(occupancy_error, weighted_error, opaque_error, layers);
    CHECK(occupancy_error < 0.01);
    CHECK(occupancy_error < 0.5 * weighted_error);
    CHECK(occupancy_error < 0.5 * opaque_error);
}

TEST_CASE("GL transparent hair is shadowed by the GL maps as the CPU's is by their read-back", "[gl][transparency]") {
    test::gl_context();
    transparent_scene s(1500);
    const gl::hair_mesh mesh(s.sc.hair);
    gl::scene_renderer renderer(s.sc);
    std::vector<std::unique_ptr<gl::maps<deep_opacity_maps<3>>>> maps;
    std::vector<deep_opacity_maps<3>> read_back;
    for (std::size_t i = 0; i < s.sc.lights.size(); ++i) {
        maps.push_back(std::make_unique<gl::maps<deep_opacity_maps<3>>>());
        maps.back()->build(mesh, s.spaces[i]);
        renderer.add_light(s.sc.lights[i], *maps.back());
        read_back.push_back(maps.back()->to_cpu());
    }
    for (std::size_t i = 0; i < s.sc.lights.size(); ++i) s.cpu_lights[i].hair = query_of(read_back[i]);
    const auto cam = camera::framing(s.sc.bounds(), 20.0f, 10.0f, 128, 128);
    for (auto mode : {transparency::occupancy, transparency::exact}) {
        renderer.set_transparency(mode, 0.4f);
        const double difference = mean_difference_linear(renderer.render(cam), render_transparent(s.sc, cam, s.cpu_lights, mode, 0.4f));
        CAPTURE(int(mode), difference);
        CHECK(difference < 2e-5);
    }
    // And the shadows are there: without them the hair is brighter.
    const transparent_scene unshadowed(1500);
    const double shadowing = mean_difference_linear(render_transparent(s.sc, cam, s.cpu_lights, transparency::exact, 0.4f),
                                                    render_transparent(unshadowed.sc, cam, unshadowed.cpu_lights, transparency::exact, 0.4f));
    CAPTURE(shadowing);
    CHECK(shadowing > 1e-3);
}

TEST_CASE("GL renders without lights show the ambient terms, as on the CPU", "[gl][transparency]") {
    test::gl_context();
    scene sc;
    sc.hair = make_procedural({.style = hair_style::wavy, .strands = 400, .segments = 8});
    sc.mesh = make_sphere({0, 0, 0}, 0.1f, 32);
    const auto cam = camera::framing(sc.bounds(), 20.0f, 10.0f, 96, 96);
    gl::scene_renderer renderer(sc);
    renderer.set_transparency(transparency::exact, 0.5f);
    const double difference = mean_difference_linear(renderer.render(cam), render_transparent(sc, cam, {}, transparency::exact, 0.5f));
    CAPTURE(difference);
    CHECK(mean_difference_linear(render_transparent(sc, cam, {}, transparency::exact, 0.5f), image(96, 96, sc.background)) > 0.01);
    CHECK(difference < 2e-5);
}

TEST_CASE("GL and CPU transparent hair agree on images of any shape", "[gl][transparency]") {
    test::gl_context();
    const transparent_scene s(600);
    gl::scene_renderer renderer(s.sc);
    s.add_lights(renderer);
    for (const auto& [w, h] : {std::pair(80, 56), std::pair(56, 80), std::pair(1, 1)}) {
        const auto cam = camera::framing(s.sc.bounds(), 20.0f, 10.0f, w, h);
        for (auto mode : {transparency::occupancy, transparency::weighted, transparency::exact}) {
            renderer.set_transparency(mode, 0.4f);
            // One pixel holds every fragment: depth peeling would take thousands of layers.
            if (w == 1 && mode == transparency::exact) continue;
            const double difference = mean_difference_linear(renderer.render(cam), render_transparent(s.sc, cam, s.cpu_lights, mode, 0.4f));
            CAPTURE(w, h, int(mode), difference);
            CHECK(difference < 2e-5);
        }
    }
}
