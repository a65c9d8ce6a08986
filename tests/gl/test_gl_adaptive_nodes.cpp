// Adaptive volumetric shadow maps on GL (node_maps_gl): the compute path's nodes against the CPU's
// tiled build, every texel bit for bit (the same fragments in the same order of values, the same
// float operations); the raster path against the CPU run on GL's own fragments; the GLSL look-up
// against the CPU query; a build whose fragments outgrow the lists' buffer; and behind sheets of
// strands.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/passes/fragment_capture.hpp>

#include "../sheets.hpp"
#include "../test_support.hpp"
#include "compute_comparison.hpp"

using namespace hairshadow;

namespace {

template <class Method>
void check_nodes_compute_path(const hair_model& model, const light_space& light, const gl::hair_mesh& mesh, const fragment_buffer& fragments) {
    Method cpu;
    cpu.build(model, light);
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light);
    gl::maps<Method> on_gl;
    on_gl.build(pass);
    const auto c = test::compare_maps(cpu, on_gl, gl::detail::read_range(*pass.textures()), test::cpu_occupancy(model, light), light.resolution());
    CAPTURE(c.occupied, c.occupancy_off, c.state_off, c.data_off);
    CHECK(c.occupied > 1000);
    CHECK(c.exact());
    CHECK(on_gl.fragment_count() == fragments.size());
    test::check_lookup_and_read_back(on_gl, cpu, test::texel_centre_queries(fragments, light, 5), 0.1f);
}

} // namespace

TEST_CASE("GL adaptive volumetric shadow maps equal the CPU maps bit for bit, and the GLSL look-up the CPU query", "[gl][avsm]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = rasterize(model, light);
    SECTION("8 nodes") { check_nodes_compute_path<adaptive_volumetric_shadow_maps<8>>(model, light, mesh, fragments); }
    SECTION("4 nodes") { check_nodes_compute_path<adaptive_volumetric_shadow_maps<4>>(model, light, mesh, fragments); }
    SECTION("16 nodes") { check_nodes_compute_path<adaptive_volumetric_shadow_maps<16>>(model, light, mesh, fragments); }
    SECTION("a rebuild whose fragments outgrow the lists walks again") {
        // A first build at 32x32 sizes the lists for its fragments; 256x256 makes more.
        gl::maps<adaptive_volumetric_shadow_maps<16>> on_gl;
        on_gl.build(mesh, light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 32));
        const auto small = on_gl.working_bytes();
        on_gl.build(mesh, light);
        CHECK(on_gl.working_bytes() > small);
        adaptive_volumetric_shadow_maps<16> cpu;
        cpu.build(model, light);
        const auto texels = on_gl.read_back();
        std::size_t differ = 0;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) differ += !(texels[std::size_t(y) * 256 + std::size_t(x)] == cpu.texel(x, y));
        CHECK(differ == 0);
    }
}

TEST_CASE("GL's raster path lists GL's fragments into the nodes the CPU makes of them", "[gl][avsm]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = gl::capture_fragments(mesh, light, raster_options{});
    adaptive_volumetric_shadow_maps<8> cpu;
    cpu.build(fragments, light);
    gl::maps<adaptive_volumetric_shadow_maps<8>> on_gl;
    on_gl.set_build_path(gl::build_path::raster);
    on_gl.build(mesh, light);
    CHECK(on_gl.fragment_count() == fragments.size());
    // GL's b = -ln(1 - alpha) rounds apart from the CPU's, which may move a node: the transmittance
    // at every fragment, not the nodes, is compared.
    const auto back = on_gl.to_cpu();
    double worst = 0;
    std::size_t queries = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            for (const auto& f : fragments.texel(x, y)) {
                const float depth = std::nextafter(f.depth, 2.0f);
                worst = std::max(worst, double(std::abs(back.transmittance(x, y, depth) - cpu.transmittance(x, y, depth))));
                ++queries;
            }
    CAPTURE(worst, queries);
    CHECK(queries > 10000);
    CHECK(worst < 0.02);
    test::check_lookup_and_read_back(on_gl, back, test::texel_centre_queries(fragments, light, 5), 0.1f);
}

TEST_CASE("the GL look-up gives the adaptive nodes' transmittance behind sheets of strands", "[gl][avsm]") {
    test::gl_context();
    const auto scene = test::make_sheets(5, 64);
    const gl::hair_mesh mesh(scene.model);
    raster_options options;
    options.fixed_alpha = 0.3f;
    adaptive_volumetric_shadow_maps<4> cpu;
    cpu.build(scene.model, scene.light, options);
    gl::maps<adaptive_volumetric_shadow_maps<4>> on_gl;
    on_gl.build(mesh, scene.light, options);
    const float y = scene.row_y[scene.row_y.size() / 2];
    std::vector<glm::vec3> points;
    for (const float z : {0.9f, 0.5f, 0.4999f, 0.4f, 0.3f, 0.2f, 0.1f, -0.05f, -0.2f, -0.3f, -0.9f}) points.push_back({0.2f, y, z});
    points.push_back({0.2f, 0.49f, -0.5f}); // a texel with no hair
    const auto t = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, points);
    for (std::size_t i = 0; i < points.size(); ++i) {
        CAPTURE(i, t[i]);
        CHECK(t[i] == Approx(cpu.transmittance(points[i])).epsilon(1e-5));
    }
    CHECK(t.front() == 1.0f);
    CHECK(t[t.size() - 2] == Approx(std::pow(0.7f, 5.0f)).epsilon(1e-5));
    CHECK(t.back() == 1.0f);
}

TEST_CASE("a GL implementation that stops long loops makes the build throw, never wrong maps", "[gl][avsm]") {
    // Sintel in a 2x2 map: tens of thousands of fragments a texel, more merge-sort steps than llvmpipe
    // runs (it ends a shader's loops after 65535 steps); in an 8x8 map, fewer. Either the build
    // throws, or its maps are the CPU's.
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const gl::hair_mesh mesh(model);
    for (const int res : {2, 8}) {
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), res);
        gl::maps<adaptive_volumetric_shadow_maps<8>> on_gl;
        adaptive_volumetric_shadow_maps<8> cpu;
        cpu.build(model, light);
        CAPTURE(res, cpu.fragment_count());
        try {
            on_gl.build(mesh, light);
        } catch (const gl::gl_error& e) {
            CHECK_THAT(e.what(), Catch::Contains("stopped the resolve pass's loops early"));
            continue;
        }
        const auto texels = on_gl.read_back();
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) CHECK(texels[std::size_t(y * res + x)] == cpu.texel(x, y));
    }
}
