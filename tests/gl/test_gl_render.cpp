// The GL renderer against the CPU renderer: the same scene, lights and method, multisampled lines
// against coverage-weighted ones.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>

#include "../test_support.hpp"

using namespace hairshadow;

namespace {
scene small_render_scene() {
    scene sc;
    sc.hair = make_procedural({.style = hair_style::wavy, .strands = 3000, .segments = 16});
    sc.mesh = make_sphere({0, 0, 0}, 0.1f, 32);
    sc.lights = {{light_spec::directional({-0.6f, -1.0f, -0.4f}), glm::vec3(1.0f)}, {light_spec::point({0.4f, 0.1f, 0.5f}), glm::vec3(0.3f, 0.35f, 0.5f)}};
    return sc;
}
} // namespace

template <class Method>
void check_renderers_agree() {
    test::gl_context();
    const auto sc = small_render_scene();
    const auto cam = camera::framing(sc.bounds(), 20.0f, 10.0f, 160, 160);
    std::vector<lit_light> cpu_lights;
    std::vector<std::unique_ptr<Method>> cpu_maps;
    std::vector<std::unique_ptr<gl::maps<Method>>> gl_maps;
    gl::hair_mesh mesh(sc.hair);
    gl::scene_renderer renderer(sc);
    for (const auto& light : sc.lights) {
        const auto space = light_space::fit(light.spec, sc.bounds(), 256);
        cpu_maps.push_back(std::make_unique<Method>());
        cpu_maps.back()->build(rasterize(sc.hair, space), space);
        cpu_lights.push_back({light, query_of(*cpu_maps.back()), depth_shadow_map(sc.mesh, space)});
        gl_maps.push_back(std::make_unique<gl::maps<Method>>());
        gl_maps.back()->build(mesh, space);
        renderer.add_light(light, *gl_maps.back());
    }
    const auto on_cpu = render_cpu(sc, cam, cpu_lights);
    const auto on_gl = renderer.render(cam);
    const double difference = mean_absolute_difference(on_cpu, on_gl);
    CAPTURE(difference);
    CHECK(mean_absolute_difference(on_cpu, image(160, 160, sc.background)) > 0.05); // the scene is there
    CHECK(difference < 0.02);
    // The hair's shadows darken both renders alike: the mean darkening against the same renderer
    // without them agrees (and is there).
    gl::scene_renderer gl_unshadowed(sc);
    std::vector<lit_light> cpu_unshadowed;
    for (const auto& light : sc.lights) {
        const auto space = light_space::fit(light.spec, sc.bounds(), 256);
        gl_unshadowed.add_unshadowed_light(light, space);
        cpu_unshadowed.push_back({light, {}, depth_shadow_map(sc.mesh, space)});
    }
    const auto darkening = [](const image& lit, const image& shadowed) {
        double sum = 0;
        for (std::size_t i = 0; i < lit.pixels.size(); ++i) sum += double(glm::dot(lit.pixels[i] - shadowed.pixels[i], glm::vec3(1.0f / 3.0f)));
        return sum / double(lit.pixels.size());
    };
    const double on_cpu_darkening = darkening(render_cpu(sc, cam, cpu_unshadowed), on_cpu);
    const double on_gl_darkening = darkening(gl_unshadowed.render(cam), on_gl);
    CAPTURE(on_cpu_darkening, on_gl_darkening);
    CHECK(on_cpu_darkening > 0.002); // linear RGB averaged over the whole image, background included
    CHECK(on_gl_darkening == Approx(on_cpu_darkening).epsilon(0.25));
}

TEST_CASE("the GL renderer draws what the CPU renderer draws", "[gl][render]") {
    SECTION("deep opacity maps 3") { check_renderers_agree<deep_opacity_maps<3>>(); }
    // 256 slices and 8 slabs: a look-up reading 5 texture units beside the mesh's depth map.
    SECTION("occupancy maps 256/8") { check_renderers_agree<occupancy_maps<256, 8>>(); }
}
