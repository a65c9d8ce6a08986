// The GL back end inside an engine: the caller's pending GL errors are left for it to read, a
// look-up that cannot be bound is refused by name, point queries restore every texture unit, the
// GLSL look-up gives the CPU query's answer at every point (bias included), and a look-up included
// under too old a #version says so.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/maps/registry.hpp>

#include "../test_support.hpp"

#include <algorithm>
#include <functional>
#include <set>
#include <vector>

using namespace hairshadow;

namespace {

/// Every GL error flag set now, read (and so cleared).
std::set<GLenum> read_errors() {
    std::set<GLenum> errors;
    for (GLenum e = glGetError(); e != GL_NO_ERROR && errors.size() < 16; e = glGetError()) errors.insert(e);
    return errors;
}

/// The 2D and 2D-array textures and the sampler of every texture unit the context has.
std::vector<GLint> every_unit() {
    GLint units = 0, active = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    std::vector<GLint> state(3 * std::size_t(units) + 1);
    for (GLint u = 0; u < units; ++u) {
        glActiveTexture(GLenum(GL_TEXTURE0 + u));
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &state[3 * std::size_t(u)]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &state[3 * std::size_t(u) + 1]);
        glGetIntegerv(GL_SAMPLER_BINDING, &state[3 * std::size_t(u) + 2]);
    }
    glActiveTexture(GLenum(active));
    state.back() = active;
    return state;
}

struct small_scene {
    hair_model model = test::grid_model(24, 8);
    light_space light = light_space::fit(light_spec::directional({0.2f, -1.0f, -0.6f}), model.bounds(), 64);
};

gl::program lookup_program(const std::string& lookup, const char* call) {
    const auto vs = gl::compile_shader(GL_VERTEX_SHADER, {"#version 430 core\n", lookup, "layout(location = 0) in vec3 p;\nvoid main() { gl_Position = vec4(",
                                                          call, "(p)); }\n"},
                                       "look-up");
    return gl::link_program({&vs}, "look-up");
}

} // namespace

TEST_CASE("the caller's pending GL errors are still pending after a build, a read-back and point queries", "[gl][state][engine]") {
    test::gl_context();
    const small_scene s;
    const gl::hair_mesh mesh(s.model);
    gl::maps<deep_opacity_maps<3>> maps;
    REQUIRE(read_errors().empty());
    const auto leave_errors = [] {
        glEnable(GLenum(0xFFFF)); // GL_INVALID_ENUM
        glLineWidth(-2.0f);       // GL_INVALID_VALUE
        glEndConditionalRender(); // GL_INVALID_OPERATION
    };
    // GL may keep one flag per kind, or (Mesa) the first error alone: what it kept is what must stay.
    leave_errors();
    const std::set<GLenum> left = read_errors();
    REQUIRE(left.count(GL_INVALID_ENUM) == 1);
    leave_errors();
    REQUIRE_NOTHROW(maps.build(mesh, s.light));
    CHECK(read_errors() == left);
    leave_errors();
    REQUIRE_NOTHROW(maps.read_back());
    CHECK(read_errors() == left);
    glEnable(GLenum(0xFFFF));
    const gl::point_queries queries(maps.lookup_source());
    const std::vector<glm::vec3> points(s.model.points.begin(), s.model.points.begin() + 10);
    REQUIRE_NOTHROW(queries.run(points, [&](GLuint prog) { maps.bind_lookup(prog); }));
    CHECK(read_errors() == std::set<GLenum>{GL_INVALID_ENUM});

    SECTION("a debug callback hears the caller's error once, not again when the library raises it back") {
        static int messages = 0;
        messages = 0;
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback([](GLenum, GLenum type, GLuint, GLenum, GLsizei, const GLchar*, const void*) { messages += type == GL_DEBUG_TYPE_ERROR; },
                               nullptr);
        glEnable(GLenum(0xFFFF));
        const int heard = messages;
        CHECK(heard == 1); // the callback works: it heard the engine's error
        maps.build(mesh, s.light);
        CHECK(messages == heard);
        CHECK(read_errors() == std::set<GLenum>{GL_INVALID_ENUM});
        glDebugMessageCallback(nullptr, nullptr);
        glDisable(GL_DEBUG_OUTPUT);
        glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        CHECK(read_errors().empty());
    }
    SECTION("each kind of error the engine can leave is still pending after a build, debug output as it was") {
        const auto incomplete_clear = [] { // GL_INVALID_FRAMEBUFFER_OPERATION
            GLuint fbo = 0;
            glGenFramebuffers(1, &fbo);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glClear(GL_COLOR_BUFFER_BIT);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glDeleteFramebuffers(1, &fbo);
        };
        const std::vector<std::pair<GLenum, std::function<void()>>> kinds = {
            {GL_INVALID_ENUM, [] { glEnable(GLenum(0xFFFF)); }},
            {GL_INVALID_VALUE, [] { glLineWidth(-2.0f); }},
            {GL_INVALID_OPERATION, [] { glEndQuery(GL_SAMPLES_PASSED); }}, // none active
            {GL_INVALID_FRAMEBUFFER_OPERATION, incomplete_clear},
            {GL_STACK_UNDERFLOW, [] { glPopDebugGroup(); }}, // only the default group on the stack
        };
        for (const bool debug_output : {false, true}) {
            if (debug_output) glEnable(GL_DEBUG_OUTPUT);
            for (const auto& [error, leave] : kinds) {
                CAPTURE(error, debug_output);
                leave();
                REQUIRE(glGetError() == error); // the engine's call raised what it should
                leave();
                maps.build(mesh, s.light);
                CHECK(read_errors() == std::set<GLenum>{error});
                CHECK(bool(glIsEnabled(GL_DEBUG_OUTPUT)) == debug_output);
            }
            glDisable(GL_DEBUG_OUTPUT);
        }
    }
}

TEST_CASE("a look-up that cannot be bound is refused, naming the missing uniform", "[gl][lookup][engine]") {
    test::gl_context();
    const small_scene s;
    const gl::hair_mesh mesh(s.model);
    gl::maps<occupancy_maps<128, 4>> maps;
    maps.build(mesh, s.light);
    const auto keyed = lookup_program(maps.lookup_source("key_"), "key_transmittance");
    REQUIRE_NOTHROW(maps.bind_lookup(keyed.get(), 0, "key_"));
    const auto before = every_unit();
    // A prefix the program does not use: nothing bound, the uniform named.
    CHECK_THROWS_WITH(maps.bind_lookup(keyed.get(), 0, "fill_"), Catch::Contains("'fill_range_map'"));
    CHECK(every_unit() == before);
    // A program that composes the look-up but never calls it keeps none of its uniforms.
    const auto unused = lookup_program(maps.lookup_source(), "float");
    CHECK_THROWS_AS(maps.bind_lookup(unused.get()), argument_error);
    CHECK_THROWS_WITH(maps.bind_lookup(0), Catch::Contains("0 is not the name of a linked program"));
    GLuint deleted = 0;
    {
        const auto p = lookup_program(maps.lookup_source(), "hs_transmittance");
        deleted = p.get();
    }
    CHECK_THROWS_WITH(maps.bind_lookup(deleted), Catch::Contains("not the name of a linked program"));
    CHECK(read_errors().empty());
}

TEST_CASE("point queries restore every texture unit, also those beyond the first eight", "[gl][state][engine]") {
    test::gl_context();
    const small_scene s;
    const gl::hair_mesh mesh(s.model);
    gl::maps<occupancy_maps<128, 4>> maps;
    maps.build(mesh, s.light);
    const auto engine_texture = gl::make_texture_2d(GL_RGBA8, 4, 4);
    GLint units = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    REQUIRE(units > 20);
    for (GLint u = 8; u < 20; ++u) {
        glActiveTexture(GLenum(GL_TEXTURE0 + u));
        glBindTexture(GL_TEXTURE_2D, engine_texture.get());
    }
    glActiveTexture(GL_TEXTURE13);
    const auto before = every_unit();
    const gl::point_queries queries(maps.lookup_source("key_") + "float hs_transmittance(vec3 p) { return key_transmittance(p); }\n");
    const std::vector<glm::vec3> points(s.model.points.begin(), s.model.points.end());
    const auto at_13 = queries.run(points, [&](GLuint prog) { maps.bind_lookup(prog, 13, "key_"); });
    CHECK(every_unit() == before);
    const auto at_0 = queries.run(points, [&](GLuint prog) { maps.bind_lookup(prog, 0, "key_"); });
    CHECK(at_13 == at_0);
    CHECK(every_unit() == before);
    maps.build(mesh, s.light);
    CHECK(every_unit() == before);
    for (GLint u = 8; u < 20; ++u) {
        glActiveTexture(GLenum(GL_TEXTURE0 + u));
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    CHECK(read_errors().empty());
}

TEST_CASE("every method's GLSL look-up gives the CPU query of its maps at every Sintel point, with and without a bias", "[gl][lookup][engine]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const gl::hair_mesh mesh(model);
    const std::vector<glm::vec3> points(model.points.begin(), model.points.end());
    // Every registered family and size (the registry's examples) with a GL twin: not the exact reference.
    std::vector<std::string> specs;
    for (const auto& text : example_specs())
        if (parse_method_spec(text).text.rfind("dsm", 0) != 0) specs.push_back(text);
    REQUIRE(specs.size() > 30);
    for (const auto& light : {light_spec::directional({0.3f, -1.0f, -0.4f}), light_spec::point({0.4f, 2.2f, 0.5f})}) {
        const auto space = light_space::fit(light, model.bounds(), 256);
        for (const auto& text : specs) {
            CAPTURE(text, space.perspective());
            auto map = gl::make_gl_shadow_map(parse_method_spec(text));
            map->build(mesh, space);
            const auto cpu = map->to_cpu();
            for (const float bias : {0.0f, 0.004f}) {
                CAPTURE(bias);
                const auto on_gl = map->transmittance(points, bias);
                std::vector<float> on_cpu(points.size());
                cpu->transmittance(points, on_cpu, {false, false, bias});
                std::size_t off = 0, shadowed = 0;
                float worst = 0.0f;
                for (std::size_t i = 0; i < points.size(); ++i) {
                    const float d = std::abs(on_gl[i] - on_cpu[i]);
                    off += !(d <= 1e-5f), worst = std::max(worst, d), shadowed += on_cpu[i] < 0.9f;
                }
                CAPTURE(off, worst, shadowed);
                CHECK(shadowed * 10 > points.size()); // the hair shadows itself: the comparison means something
                CHECK(off == 0);
            }
        }
    }
}

TEST_CASE("a look-up included under #version 330 fails with a message naming the version it needs", "[gl][lookup][engine]") {
    test::gl_context();
    const std::string lookup = gl::maps<deep_opacity_maps<3>>::lookup_source();
    CHECK(lookup.rfind("// hairshadow's look-up: GLSL 4.30 or newer", 0) == 0);
    try {
        gl::compile_shader(GL_VERTEX_SHADER, {"#version 330 core\n", lookup, "in vec3 p;\nvoid main() { gl_Position = vec4(hs_transmittance(p)); }\n"},
                           "old look-up");
        FAIL("a #version 330 shader compiled the look-up");
    } catch (const gl::gl_error& e) {
        CHECK_THAT(e.what(), Catch::Contains("needs GLSL 4.30 or newer"));
    }
}
