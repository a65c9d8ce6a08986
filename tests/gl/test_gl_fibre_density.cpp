// Approximate deep shadow maps on GL's raster path against the CPU kernels, both built from the fragments GL
// rasterised: the depth map and the measured sums read back, and the GLSL look-up against the CPU
// query; TressFX's parameters reach the look-up.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/passes/fragment_capture.hpp>

#include "../sheets.hpp"
#include "../test_support.hpp"

#include <cstring>

using namespace hairshadow;

namespace {

template <class Method>
void check_fibre_density(const Method& parameters, const light_space& light, const gl::hair_mesh& mesh, const fragment_buffer& fragments) {
    Method cpu = parameters;
    cpu.build(fragments, light);
    gl::maps<Method> on_gl(parameters);
    on_gl.set_build_path(gl::build_path::raster); // the papers' passes, against the CPU run on GL's own fragments
    on_gl.build(mesh, light);
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long state_off = 0, data_off = 0, occupied = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            occupied += !fragments.texel(x, y).empty();
            state_off += std::memcmp(&c.placement, &g.placement, sizeof(c.placement)) != 0; // MIN / MAX blending: bit-exact
            if constexpr (requires { c.data.fragments; })
                data_off += c.data.fragments != g.data.fragments ||
                            std::abs(c.data.optical_depth - g.data.optical_depth) > 1e-5f * std::max(c.data.optical_depth, 1e-3f);
            else data_off += c.data.any != g.data.any;
        }
    CHECK(occupied > 1000);
    CHECK(state_off == 0);
    CHECK(data_off == 0);

    test::check_lookup_and_read_back(on_gl, cpu, test::texel_centre_queries(fragments, light, 5), 0.25f);
}

} // namespace

TEST_CASE("GL approximate deep shadow maps equal the CPU maps, and the GLSL look-up the CPU query", "[gl][adsm]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = gl::capture_fragments(mesh, light, raster_options{});
    SECTION("TressFX's defaults") { check_fibre_density(approximate_deep_shadow_maps(), light, mesh, fragments); }
    SECTION("sparser fibres, more transparent") {
        check_fibre_density(approximate_deep_shadow_maps(per_pixel_depth<1>(), fibre_density<>({.spacing = 1.0f, .radius = 0.01f, .alpha = 0.1f})),
                            light, mesh, fragments);
    }
    SECTION("measured density") { check_fibre_density(measured_density_shadow_maps(), light, mesh, fragments); }
}

TEST_CASE("the GL look-up gives TressFX's transmittance behind sheets of strands", "[gl][adsm]") {
    test::gl_context();
    const auto scene = test::make_sheets(3, 64);
    const gl::hair_mesh mesh(scene.model);
    const approximate_deep_shadow_maps parameters(per_pixel_depth<1>(), fibre_density<>({.spacing = 0.5f, .radius = 0.2f, .alpha = 0.3f}));
    gl::maps<approximate_deep_shadow_maps> on_gl(parameters);
    on_gl.set_build_path(gl::build_path::raster); // the papers' passes, against the CPU run on GL's own fragments
    on_gl.build(mesh, scene.light);
    const float y = scene.row_y[scene.row_y.size() / 2];
    const std::vector<glm::vec3> points = {{0.2f, y, 0.9f}, {0.2f, y, 0.45f}, {0.2f, y, 0.3f}, {0.2f, y, -0.5f}, {0.2f, 0.49f, -0.5f}};
    const auto t = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, points);
    CHECK(t[0] == 1.0f);
    CHECK(t[1] == Approx(0.7f).epsilon(1e-5));
    CHECK(t[2] == Approx(0.49f).epsilon(1e-4));
    CHECK(t[3] == Approx(std::pow(0.7f, 10.0f)).epsilon(1e-4));
    CHECK(t[4] == 1.0f); // a texel with no hair
    // New parameters reach the look-up without a rebuild: at most 5 fibres, alpha 0.5.
    on_gl.set_parameters({.spacing = 0.5f, .radius = 0.2f, .alpha = 0.5f, .max_fibres = 5});
    const auto capped = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, points);
    CHECK(capped[2] == Approx(0.25f).epsilon(1e-4));
    CHECK(capped[3] == Approx(std::pow(0.5f, 5.0f)).epsilon(1e-4));
    CHECK_THROWS_AS(on_gl.set_parameters({.alpha = 1.0f}), argument_error);
    CHECK(gl::maps<approximate_deep_shadow_maps>::texture_units == 1);
    CHECK(gl::maps<measured_density_shadow_maps>::texture_units == 2);
}
