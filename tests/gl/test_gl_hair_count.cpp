// Unreal Engine's hair-count deep shadows on GL (interpolated_maps_gl with hair_count's look-up): the
// compute path's maps against the CPU's tiled build (every texel, as the compute test does for the
// default parameters, here with others), the GLSL look-up against the CPU query with the parameters
// reaching it, the maps read back with them, the raster path against the CPU run on GL's own
// fragments, and the look-up behind sheets of strands.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/passes/fragment_capture.hpp>

#include "../sheets.hpp"
#include "../test_support.hpp"

#include <cstring>

using namespace hairshadow;

namespace {

template <class Method>
void check_hair_count(const Method& parameters, const hair_model& model, const light_space& light, const gl::hair_mesh& mesh, const fragment_buffer& fragments) {
    Method cpu = parameters;
    cpu.build(model, light);
    gl::maps<Method> on_gl(parameters);
    on_gl.build(mesh, light); // the compute path: the CPU's maps, states bit for bit
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long state_off = 0, data_off = 0, occupied = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            occupied += !fragments.texel(x, y).empty();
            state_off += std::memcmp(&c.placement, &g.placement, sizeof(c.placement)) != 0;
            for (int k = 0; k < Method::layer_count; ++k) {
                const float a = cpu.stored_optical_depth(x, y, k), b = Method::reconstruction_type::template stored_optical_depth<
                                                                   typename Method::placement_type, typename Method::accumulation_type>(g.data, k);
                data_off += std::abs(a - b) > 1e-6f * std::max(a, 1.0f);
            }
        }
    CHECK(occupied > 1000);
    CHECK(state_off == 0);
    CHECK(data_off == 0);

    test::check_lookup_and_read_back(on_gl, cpu, test::texel_centre_queries(fragments, light, 5), 0.1f);
    CHECK(on_gl.to_cpu().reconstruction().parameters() == parameters.reconstruction().parameters()); // the same hair
}

} // namespace

TEST_CASE("GL hair-count deep shadows equal the CPU maps, and the GLSL look-up the CPU query", "[gl][ue]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = rasterize(model, light);
    SECTION("Unreal's defaults") { check_hair_count(hair_count_deep_shadows<4>(), model, light, mesh, fragments); }
    SECTION("another hair and distribution, eight layers") {
        check_hair_count(hair_count_deep_shadows<8>(power_layers<8>(0.2f), hair_count({.hair_alpha = 0.3f})), model, light, mesh, fragments);
    }
    SECTION("counted from zero, 8-bit") {
        check_hair_count(hair_count_deep_shadows<4, emulated_8bit>(power_layers<4>(0.8f), hair_count({.minus_one = false})), model, light, mesh, fragments);
    }
}

TEST_CASE("GL's raster path draws Unreal's layers as the CPU builds them from GL's fragments", "[gl][ue]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = gl::capture_fragments(mesh, light, raster_options{});
    hair_count_deep_shadows<4> cpu;
    cpu.build(fragments, light);
    gl::maps<hair_count_deep_shadows<4>> on_gl;
    on_gl.set_build_path(gl::build_path::raster); // additive blending of each fragment's b into the layers it reaches
    on_gl.build(mesh, light);
    const auto texels = on_gl.read_back();
    long state_off = 0, data_off = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * 256 + std::size_t(x)];
            state_off += std::memcmp(&c.placement, &g.placement, sizeof(c.placement)) != 0; // MIN blending: bit-exact
            for (std::size_t k = 0; k < 4; ++k) data_off += std::abs(c.data.layers[k] - g.data.layers[k]) > 1e-5f * std::max(c.data.layers[k], 1.0f);
        }
    CHECK(state_off == 0);
    CHECK(data_off == 0);
    test::check_lookup_and_read_back(on_gl, cpu, test::texel_centre_queries(fragments, light, 5), 0.1f);
}

TEST_CASE("the GL look-up gives Unreal's A^max(0, count - 1) behind sheets of strands", "[gl][ue]") {
    test::gl_context();
    const auto scene = test::make_sheets(5, 64);
    const gl::hair_mesh mesh(scene.model);
    raster_options options;
    options.fixed_alpha = 0.3f;
    const hair_count_deep_shadows<4> parameters(power_layers<4>(), hair_count({.hair_alpha = 0.3f}));
    gl::maps<hair_count_deep_shadows<4>> on_gl(parameters);
    on_gl.build(mesh, scene.light, options);
    const float y = scene.row_y[scene.row_y.size() / 2];
    const std::vector<glm::vec3> points = {{0.2f, y, 0.9f}, {0.2f, y, 0.45f}, {0.2f, y, -0.9f}, {0.2f, 0.49f, -0.5f}};
    const auto t = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, points);
    CHECK(t[0] == 1.0f);
    CHECK(t[1] == 1.0f);                           // one sheet in front, less the hair's own
    CHECK(t[2] == Approx(0.7f).epsilon(1e-5));     // two sheets counted (the last three lie behind the last layer), less one
    CHECK(t[3] == 1.0f);                           // a texel with no hair

    // Counted from zero, just behind the first sheet, inside the first layer (0.003 of the hair's
    // depth), where the query's bias (0.05 of that layer) moves T by a few hundredths: GL as the CPU.
    const hair_count_deep_shadows<4> zero(power_layers<4>(), hair_count({.hair_alpha = 0.3f, .minus_one = false}));
    gl::maps<hair_count_deep_shadows<4>> zero_gl(zero);
    zero_gl.build(mesh, scene.light, options);
    auto zero_cpu = zero;
    zero_cpu.build(scene.model, scene.light, options);
    const std::vector<glm::vec3> near_front = {{0.2f, y, 0.4997f}, {0.2f, y, 0.4992f}, {0.2f, y, 0.4985f}};
    const auto g = test::gl_lookup(zero_gl.lookup_source(), [&](GLuint p) { zero_gl.bind_lookup(p); }, near_front);
    for (std::size_t i = 0; i < near_front.size(); ++i) {
        CAPTURE(i, g[i]);
        CHECK(zero_cpu.transmittance(near_front[i]) < 0.99f);
        CHECK(g[i] == Approx(zero_cpu.transmittance(near_front[i])).epsilon(1e-5));
    }
}
