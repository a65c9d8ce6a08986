// GLSL look-ups composed: two methods' look-ups, under different prefixes, in one shader; every
// method's with any other's; prefixes that must make valid GLSL names.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/maps/registry.hpp>

#include "../test_support.hpp"

#include <algorithm>
#include <array>
#include <tuple>

using namespace hairshadow;

TEST_CASE("two prefixed look-ups of different methods and lights shade in one shader", "[gl][state][lookup]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const gl::hair_mesh mesh(model);
    const auto key_light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const auto fill_light = light_space::fit(light_spec::directional({1, -0.5f, 0.3f}), model.bounds(), 200);
    gl::maps<deep_opacity_maps<3>> key;
    gl::maps<occupancy_maps<128, 4>> fill;
    key.build(mesh, key_light);
    fill.build(mesh, fill_light);
    STATIC_REQUIRE(gl::maps<deep_opacity_maps<3>>::texture_units == 2);
    STATIC_REQUIRE(gl::maps<occupancy_maps<128, 4>>::texture_units == 3);

    // One program: key_transmittance and fill_transmittance side by side, on units [0, 2) and [2, 5).
    const std::string lookups = key.lookup_source("key_") + fill.lookup_source("fill_");
    CHECK(lookups.find("hs_") == std::string::npos);
    CHECK(lookups.find("HS_") == std::string::npos);
    const std::string source = lookups + "uniform int which_light;\n"
                                         "float hs_transmittance(vec3 p) { return which_light == 0 ? key_transmittance(p) : fill_transmittance(p); }\n";
    const gl::point_queries queries(source);
    std::vector<glm::vec3> points(model.points.begin(), model.points.end());
    const auto key_cpu = key.to_cpu();
    const auto fill_cpu = fill.to_cpu();
    for (int which : {0, 1}) {
        const auto on_gpu = queries.run(points, [&](GLuint prog) {
            key.bind_lookup(prog, 0, "key_");
            fill.bind_lookup(prog, gl::maps<deep_opacity_maps<3>>::texture_units, "fill_");
            glProgramUniform1i(prog, glGetUniformLocation(prog, "which_light"), which);
        });
        std::vector<float> on_cpu(points.size());
        if (which == 0) key_cpu.transmittance(points, on_cpu);
        else fill_cpu.transmittance(points, on_cpu);
        std::size_t off = 0, shadowed = 0;
        for (std::size_t i = 0; i < points.size(); ++i) off += !(std::abs(on_gpu[i] - on_cpu[i]) <= 1e-5f), shadowed += on_cpu[i] < 0.9f;
        CAPTURE(which, off, shadowed, points.size());
        CHECK(shadowed * 4 > points.size());
        CHECK(off == 0); // the look-up finds the CPU query's texel and depth, even on texel edges
    }
}

TEST_CASE("every method's look-up composes with any other's under different prefixes", "[gl][lookup]") {
    test::gl_context();
    const std::vector<std::string> specs = {"osm:16", "osm:8:gamma", "dom:3", "dom:4:8bit", "dc:4", "occ:128:4", "rosm:16", "adsm", "adsm:auto", "ue", "ue:8:zero"};
    for (const auto& a : specs)
        for (const auto& b : specs) {
            const auto first = gl::make_gl_shadow_map(parse_method_spec(a)), second = gl::make_gl_shadow_map(parse_method_spec(b));
            CAPTURE(a, b);
            CHECK_NOTHROW(gl::compile_shader(GL_VERTEX_SHADER,
                                             {"#version 430 core\n", first->lookup_source("a_"), second->lookup_source("b_"),
                                              "void main() { gl_Position = vec4(a_transmittance(vec3(0.0)) * b_transmittance(vec3(1.0))); }\n"},
                                             a + " and " + b));
        }
}

TEST_CASE("look-up prefixes must make valid GLSL names", "[gl][lookup][errors]") {
    for (const char* bad : {"", "1key_", "key__", "gl_key_", "GL_", "key-", "key light", "a_very_long_prefix_that_goes_on_and_on_"})
        CHECK_THROWS_AS(gl::prefix_glsl("float hs_x;", bad), argument_error);
    CHECK(gl::prefix_glsl("#ifdef HS_LAYERS\nfloat hs_x = ths_y + HS_Z; // hs_x\n", "key_") == "#ifdef KEY_LAYERS\nfloat key_x = ths_y + KEY_Z; // key_x\n");
    CHECK(gl::prefix_glsl("hs_x", "hs_") == "hs_x");
}
