// The GL back end's state contract (README, "The GL state contract"): builds and look-up bindings leave
// a hostile engine's state as they found it and build the same maps as from a clean state; several
// methods share one light pass (look-ups composed in one shader: test_gl_lookup_composition.cpp).
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>
#include <hairshadow/gl/maps/registry.hpp>

#include "../test_support.hpp"

#include <algorithm>
#include <array>
#include <tuple>

using namespace hairshadow;

namespace {

/// The engine state the contract covers, read by the test's own queries (not the library's guard).
struct engine_state {
    GLint program = 0, draw_fbo = 0, read_fbo = 0, vao = 0, array_buffer = 0, active_texture = 0, pack_buffer = 0, storage_buffer = 0;
    std::array<GLint, 4> viewport{}, scissor_box{};
    /// Every viewport (up to 16, the most the guard saves), with its scissor box, scissor test and depth range.
    GLint viewport_count = 0;
    std::array<std::array<GLfloat, 4>, 16> viewports{};
    std::array<std::array<GLint, 4>, 16> scissor_boxes{};
    std::array<GLboolean, 16> scissor_tests{};
    std::array<std::array<GLdouble, 2>, 16> depth_ranges{};
    GLboolean scissor = 0, depth_test = 0, stencil_test = 0, cull = 0, logic_op = 0, discard = 0, dither = 0, depth_clamp = 0, restart = 0,
              line_smooth = 0, clip_distance = 0;
    GLint cull_mode = 0, logic_op_mode = 0, pack_alignment = 0, pack_row_length = 0, clip_origin = 0, clip_depth = 0;
    std::array<GLint, 2> polygon_mode{};
    std::array<std::array<GLboolean, 4>, 8> masks{};
    std::array<GLboolean, 8> blend{};
    std::array<std::array<GLint, 6>, 8> blend_functions{};
    std::array<std::array<GLint, 3>, 8> units{}; // 2D, 2D array, sampler
    std::array<std::array<GLint, 2>, 4> images{};      // units 0 to 3: name, format
    std::array<std::array<GLint64, 3>, 8> storage{};   // indexed storage bindings 0 to 7: name, start, size
    GLfloat line_width = 0;
    friend bool operator==(const engine_state&, const engine_state&) = default;

    static engine_state read() {
        engine_state s;
        glGetIntegerv(GL_CURRENT_PROGRAM, &s.program);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.draw_fbo);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.read_fbo);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vao);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s.array_buffer);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &s.active_texture);
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &s.pack_buffer);
        glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s.storage_buffer);
        glGetIntegerv(GL_VIEWPORT, s.viewport.data());
        glGetIntegerv(GL_SCISSOR_BOX, s.scissor_box.data());
        glGetIntegerv(GL_MAX_VIEWPORTS, &s.viewport_count);
        s.viewport_count = std::min(s.viewport_count, GLint(s.viewports.size()));
        for (GLuint i = 0; i < GLuint(s.viewport_count); ++i) {
            glGetFloati_v(GL_VIEWPORT, i, s.viewports[i].data());
            glGetIntegeri_v(GL_SCISSOR_BOX, i, s.scissor_boxes[i].data());
            s.scissor_tests[i] = glIsEnabledi(GL_SCISSOR_TEST, i);
            glGetDoublei_v(GL_DEPTH_RANGE, i, s.depth_ranges[i].data());
        }
        for (auto [cap, out] : {std::pair{GL_SCISSOR_TEST, &s.scissor}, {GL_DEPTH_TEST, &s.depth_test}, {GL_STENCIL_TEST, &s.stencil_test},
                                {GL_CULL_FACE, &s.cull}, {GL_COLOR_LOGIC_OP, &s.logic_op}, {GL_RASTERIZER_DISCARD, &s.discard},
                                {GL_DITHER, &s.dither}, {GL_DEPTH_CLAMP, &s.depth_clamp}, {GL_PRIMITIVE_RESTART, &s.restart},
                                {GL_LINE_SMOOTH, &s.line_smooth}, {GL_CLIP_DISTANCE0, &s.clip_distance}})
            *out = glIsEnabled(cap);
        glGetIntegerv(GL_CULL_FACE_MODE, &s.cull_mode);
        glGetIntegerv(GL_LOGIC_OP_MODE, &s.logic_op_mode);
        glGetIntegerv(GL_PACK_ALIGNMENT, &s.pack_alignment);
        glGetIntegerv(GL_PACK_ROW_LENGTH, &s.pack_row_length);
        glGetIntegerv(GL_CLIP_ORIGIN, &s.clip_origin);
        glGetIntegerv(GL_CLIP_DEPTH_MODE, &s.clip_depth);
        glGetIntegerv(GL_POLYGON_MODE, s.polygon_mode.data());
        glGetFloatv(GL_LINE_WIDTH, &s.line_width);
        for (GLuint i = 0; i < 8; ++i) {
            glGetBooleani_v(GL_COLOR_WRITEMASK, i, s.masks[i].data());
            s.blend[i] = glIsEnabledi(GL_BLEND, i);
            const GLenum names[6] = {GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA, GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA};
            for (int k = 0; k < 6; ++k) glGetIntegeri_v(names[k], i, &s.blend_functions[i][std::size_t(k)]);
        }
        for (int u = 0; u < 8; ++u) {
            glActiveTexture(GLenum(GL_TEXTURE0 + u));
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &s.units[std::size_t(u)][0]);
            glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &s.units[std::size_t(u)][1]);
            glGetIntegerv(GL_SAMPLER_BINDING, &s.units[std::size_t(u)][2]);
        }
        glActiveTexture(GLenum(s.active_texture));
        for (GLuint i = 0; i < 4; ++i) {
            glGetIntegeri_v(GL_IMAGE_BINDING_NAME, i, &s.images[i][0]);
            glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, i, &s.images[i][1]);
        }
        for (GLuint i = 0; i < 8; ++i) {
            GLint name = 0;
            glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &name);
            s.storage[i][0] = name;
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &s.storage[i][1]);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &s.storage[i][2]);
        }
        return s;
    }
};

/// What an engine may leave bound and set between its passes, every piece of it unlike GL's defaults.
class hostile_engine {
public:
    hostile_engine() {
        const auto vs = gl::compile_shader(GL_VERTEX_SHADER, {"#version 430 core\nvoid main() { gl_Position = vec4(0.0); }\n"}, "engine vertex");
        program_ = gl::link_program({&vs}, "engine program");
        colour_ = gl::make_texture_2d(GL_RGBA8, 64, 64);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
        glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, colour_.get(), 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        array_texture_ = gl::make_texture();
        glBindTexture(GL_TEXTURE_2D_ARRAY, array_texture_.get());
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA8, 4, 4, 2);
        glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
        glGenSamplers(1, &sampler_);
        glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR); // makes one-level textures incomplete
        glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_.get());
        glBufferData(GL_PIXEL_PACK_BUFFER, 64, nullptr, GL_STREAM_READ);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, storage_.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, 1024, nullptr, GL_DYNAMIC_DRAW);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    }
    ~hostile_engine() { glDeleteSamplers(1, &sampler_); }

    /// Sets the hostile state, and leaves a GL error unread.
    void apply() const {
        glUseProgram(program_.get());
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_.get());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
        glBindVertexArray(vao_.get());
        glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
        glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_.get());
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer_.get());
        glViewport(3, 5, 17, 19);
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, 64, 64);
        // Then every other viewport its own rectangle, scissor box, scissor test and depth range (a
        // layered renderer's cube-map or cascade viewports): the passes' glViewport sets them all.
        GLint viewports = 0;
        glGetIntegerv(GL_MAX_VIEWPORTS, &viewports);
        REQUIRE(viewports >= 16); // GL 4.1's minimum
        for (GLuint i = 1; i < GLuint(viewports); ++i) {
            glViewportIndexedf(i, float(2 * i), float(i), float(20 + i), float(30 - i));
            glScissorIndexed(i, GLint(i), GLint(3 * i), GLsizei(40 - i), GLsizei(10 + i));
            if (i % 3) glEnablei(GL_SCISSOR_TEST, i);
            else glDisablei(GL_SCISSOR_TEST, i);
            glDepthRangeIndexed(i, 0.05 * double(i), 1.0 - 0.01 * double(i));
        }
        glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
        glEnable(GL_BLEND);
        glBlendEquationSeparate(GL_FUNC_REVERSE_SUBTRACT, GL_MAX);
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_DST_COLOR, GL_ZERO);
        glEnable(GL_DEPTH_TEST);
        glEnable(GL_STENCIL_TEST);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT_AND_BACK);
        glEnable(GL_COLOR_LOGIC_OP);
        glLogicOp(GL_XOR);
        glEnable(GL_RASTERIZER_DISCARD);
        glDisable(GL_DITHER);
        glEnable(GL_DEPTH_CLAMP);
        glEnable(GL_PRIMITIVE_RESTART);
        glEnable(GL_LINE_SMOOTH);     // antialiased lines would change every fragment's coverage
        glEnable(GL_CLIP_DISTANCE0); // the library's shaders write no gl_ClipDistance: undefined clipping
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
        glPixelStorei(GL_PACK_ALIGNMENT, 8);
        glPixelStorei(GL_PACK_ROW_LENGTH, 7);
        for (GLuint u = 0; u < 8; ++u) glBindSampler(u, sampler_);
        for (GLuint i = 0; i < 4; ++i) glBindImageTexture(i, colour_.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
        // The compute build's storage bindings, each a range of the engine's buffer.
        for (GLuint i = 0; i < 8; ++i) glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, storage_.get(), GLintptr(64 * i), 64);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer_.get());
        glActiveTexture(GL_TEXTURE5);
        glBindTexture(GL_TEXTURE_2D, colour_.get());
        glBindTexture(GL_TEXTURE_2D_ARRAY, array_texture_.get());
        for (GLenum unit : {GL_TEXTURE0, GL_TEXTURE1, GL_TEXTURE2}) {
            glActiveTexture(unit);
            glBindTexture(GL_TEXTURE_2D, colour_.get());
        }
        glActiveTexture(GL_TEXTURE5);
        REQUIRE(glGetError() == GL_NO_ERROR);
        glEnable(GLenum(0x7fff)); // the unread error: GL_INVALID_ENUM
    }

    /// Back to GL's defaults, for the clean builds.
    static void reset() {
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        glDisable(GL_SCISSOR_TEST);
        glDepthRange(0.0, 1.0);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDisable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ZERO);
        for (GLenum cap : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_CULL_FACE, GL_COLOR_LOGIC_OP, GL_RASTERIZER_DISCARD, GL_DEPTH_CLAMP, GL_PRIMITIVE_RESTART,
                           GL_LINE_SMOOTH, GL_CLIP_DISTANCE0})
            glDisable(cap);
        glEnable(GL_DITHER);
        glCullFace(GL_BACK);
        glLogicOp(GL_COPY);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        for (GLuint u = 0; u < 8; ++u) {
            glBindSampler(u, 0);
            glActiveTexture(GL_TEXTURE0 + u);
            glBindTexture(GL_TEXTURE_2D, 0);
            glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
        }
        glActiveTexture(GL_TEXTURE0);
        for (GLuint i = 0; i < 4; ++i) glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
        for (GLuint i = 0; i < 8; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, 0);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        REQUIRE(glGetError() == GL_NO_ERROR);
    }

private:
    gl::program program_;
    gl::framebuffer fbo_ = gl::make_framebuffer();
    gl::texture colour_, array_texture_;
    gl::vertex_array vao_ = gl::make_vertex_array();
    gl::buffer buffer_ = gl::make_buffer(), pack_ = gl::make_buffer(), storage_ = gl::make_buffer();
    GLuint sampler_ = 0;
};

struct test_scene {
    hair_model model = test::grid_model(40, 12);
    light_space light = light_space::fit(light_spec::directional({0.2f, -1.0f, -0.6f}), model.bounds(), 96);
};

/// Builds `Method` on GL from a clean state and from the hostile one, on both build paths: the state
/// comes back unchanged after the build and after the read-back, and the maps are equal.
template <class Method>
void check_contract(const gl::hair_mesh& mesh, const light_space& light, gl::build_path path);
template <class Method>
void check_contract(const gl::hair_mesh& mesh, const light_space& light) {
    for (const auto path : {gl::build_path::compute, gl::build_path::raster}) {
        CAPTURE(gl::to_string(path));
        check_contract<Method>(mesh, light, path);
    }
}
template <class Method>
void check_contract(const gl::hair_mesh& mesh, const light_space& light, gl::build_path path) {
    hostile_engine::reset();
    gl::maps<Method> clean;
    clean.set_build_path(path);
    clean.build(mesh, light);
    const auto expected = clean.read_back();

    const hostile_engine engine;
    gl::maps<Method> hostile;
    hostile.set_build_path(path);
    engine.apply();
    const auto before = engine_state::read();
    REQUIRE_NOTHROW(hostile.build(mesh, light)); // the caller's unread error does not fail it
    CHECK(engine_state::read() == before);
    CHECK(glGetError() == GL_INVALID_ENUM); // the engine's own, left for it to read
    CHECK(glGetError() == GL_NO_ERROR);     // and the library's passes raised none
    const auto texels = hostile.read_back();
    CHECK(engine_state::read() == before);
    GLuint lookup_program = 0;
    {
        const auto vs = gl::compile_shader(GL_VERTEX_SHADER,
                                           {"#version 430 core\n", hostile.lookup_source(),
                                            "layout(location = 0) in vec3 p; void main() { gl_Position = vec4(hs_transmittance(p)); }\n"},
                                           "look-up");
        auto prog = gl::link_program({&vs}, "look-up");
        lookup_program = prog.get();
        hostile.bind_lookup(lookup_program, 9); // not the current program: uniforms set all the same
        auto after_bind = engine_state::read();
        CHECK(glGetError() == GL_NO_ERROR);
        CHECK(after_bind.program == before.program);
        CHECK(after_bind.active_texture == before.active_texture);
        GLint unit = -1;
        glGetUniformiv(lookup_program, glGetUniformLocation(lookup_program, "hs_range_map"), &unit);
        CHECK(unit == 9);
    }
    std::size_t differing = 0;
    REQUIRE(texels.size() == expected.size());
    for (std::size_t i = 0; i < texels.size(); ++i) differing += !(texels[i] == expected[i]);
    CAPTURE(differing);
    CHECK(differing == 0);
    hostile_engine::reset();
}

} // namespace

TEST_CASE("GL builds leave a hostile engine's state as they found it and build the maps a clean state builds", "[gl][state]") {
    test::gl_context();
    const test_scene s;
    const gl::hair_mesh mesh(s.model);
    SECTION("opacity shadow maps") { check_contract<opacity_shadow_maps<16>>(mesh, s.light); }
    SECTION("opacity shadow maps, gamma spacing, 8-bit") { check_contract<opacity_shadow_maps<16, gamma_spacing, emulated_8bit>>(mesh, s.light); }
    SECTION("deep opacity maps") { check_contract<deep_opacity_maps<3>>(mesh, s.light); }
    SECTION("deep opacity maps, 8-bit") { check_contract<deep_opacity_maps_8bit<3>>(mesh, s.light); }
    SECTION("density clustering") { check_contract<density_clustering<4>>(mesh, s.light); }
    SECTION("occupancy maps") { check_contract<occupancy_maps<128, 4>>(mesh, s.light); }
    SECTION("range opacity maps") { check_contract<range_opacity_maps<16>>(mesh, s.light); }
    SECTION("approximate deep shadow maps") { check_contract<approximate_deep_shadow_maps>(mesh, s.light); }
    SECTION("measured fibre density") { check_contract<measured_density_shadow_maps>(mesh, s.light); }
}

TEST_CASE("the hair mesh's upload leaves the caller's vertex array and array buffer bound", "[gl][state]") {
    test::gl_context();
    const hostile_engine engine;
    engine.apply();
    const auto before = engine_state::read();
    const gl::hair_mesh mesh(test::grid_model(3, 4));
    CHECK(engine_state::read() == before);
    CHECK(glGetError() == GL_INVALID_ENUM); // the engine's unread error, still its own to read
    hostile_engine::reset();
}

TEST_CASE("meshes over the user's buffers, update and update_hair leave the caller's state as they found it", "[gl][state][motion]") {
    test::gl_context();
    scene sc;
    sc.hair = test::grid_model(3, 4); // strands of 4 points
    gl::scene_renderer renderer(sc);
    gl::hair_mesh own(sc.hair);
    gl::buffer points_buffer = gl::make_buffer(), index_buffer = gl::make_buffer();
    std::vector<float> xyz;
    for (const auto& p : sc.hair.points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    const std::uint32_t pairs[2] = {0, 1};
    glBindBuffer(GL_ARRAY_BUFFER, points_buffer.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(xyz.size() * sizeof(float)), xyz.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, index_buffer.get());
    glBufferData(GL_ARRAY_BUFFER, sizeof pairs, pairs, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    gl::point_buffers points;
    points.point_count = sc.hair.point_count();
    points.positions = {points_buffer.get(), 0, 0};
    points.uniform_thickness = 0.01f;

    const hostile_engine engine;
    engine.apply();
    // The engine's vertex array (bound by apply) holds an element buffer and instanced attributes.
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer.get());
    for (GLuint a = 0; a < 3; ++a) glVertexAttribDivisor(a, a + 2);
    const auto before = engine_state::read();
    const auto vertex_array_state = [] {
        std::array<GLint, 4> v{};
        glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &v[0]);
        for (GLuint a = 0; a < 3; ++a) glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_DIVISOR, &v[a + 1]);
        return v;
    };
    const auto engine_vertex_array = vertex_array_state();
    {
        const gl::hair_mesh strands(points, gl::strand_segments{3, 4});
        const gl::hair_mesh indexed(points, gl::index_segments{index_buffer.get(), 0, 1});
    }
    own.update(sc.hair.points);
    renderer.update_hair();
    CHECK(engine_state::read() == before);
    CHECK(vertex_array_state() == engine_vertex_array);
    CHECK(glGetError() == GL_INVALID_ENUM); // the engine's unread error, still its own to read
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    for (GLuint a = 0; a < 3; ++a) glVertexAttribDivisor(a, 0);
    hostile_engine::reset();
}

TEST_CASE("methods for one light share one light pass and build the maps their own passes build", "[gl][state]") {
    test::gl_context();
    const test_scene s;
    const gl::hair_mesh mesh(s.model);
    gl::light_pass pass;
    gl::maps<deep_opacity_maps<3>> dom_shared, dom_own;
    gl::maps<occupancy_maps<128, 4>> occ_shared, occ_own;
    CHECK_THROWS_AS(dom_shared.build(pass), argument_error); // the pass has not run
    pass.run(mesh, s.light);
    dom_shared.build(pass);
    occ_shared.build(pass);
    dom_own.build(mesh, s.light);
    occ_own.build(mesh, s.light);
    CHECK(dom_shared.read_back() == dom_own.read_back());
    CHECK(occ_shared.read_back() == occ_own.read_back());
    CHECK(dom_shared.placement().extent() == dom_own.placement().extent());

    // After the pass runs again, maps built from its earlier run refuse to bind, rather than shade wrong.
    const auto other = light_space::fit(light_spec::directional({1, 0, 0}), s.model.bounds(), 96);
    pass.run(mesh, other);
    {
        const auto vs = gl::compile_shader(GL_VERTEX_SHADER,
                                           {"#version 430 core\n", dom_shared.lookup_source(), "in vec3 p;\nvoid main() { gl_Position = vec4(hs_transmittance(p)); }\n"},
                                           "look-up");
        const auto prog = gl::link_program({&vs}, "look-up");
        CHECK_THROWS_WITH(dom_shared.bind_lookup(prog.get()), Catch::Contains("has run again"));
    }
    CHECK_THROWS_WITH(dom_shared.read_back(), Catch::Contains("has run again"));
    dom_shared.build(pass);
    CHECK_NOTHROW(dom_shared.read_back());

    // Maps switching between their own pass and a shared one give each build's own placement.
    gl::maps<deep_opacity_maps<3>> dom_other;
    dom_other.build(mesh, other);
    dom_own.build(mesh, s.light);
    const float own_extent = dom_own.placement().extent();
    dom_own.build(pass); // the shared pass, now from `other`
    CHECK(dom_own.placement().extent() == dom_other.placement().extent());
    CHECK(dom_own.placement().extent() != own_extent);

    // A new resolution gives the pass new textures: the maps built before keep theirs, still valid.
    pass.run(mesh, light_space::fit(light_spec::directional({1, 0, 0}), s.model.bounds(), 64));
    CHECK_NOTHROW(dom_shared.read_back());
}

TEST_CASE("a rebuild at a new resolution, with the old maps bound for a look-up, raises no GL error", "[gl][state]") {
    test::gl_context();
    const test_scene s;
    const gl::hair_mesh mesh(s.model);
    gl::maps<occupancy_maps<128, 4>> occ;
    occ.build(mesh, s.light);
    const auto vs = gl::compile_shader(GL_VERTEX_SHADER,
                                       {"#version 430 core\n", occ.lookup_source(), "void main() { gl_Position = vec4(hs_transmittance(vec3(0.0))); }\n"},
                                       "look-up");
    const auto prog = gl::link_program({&vs}, "look-up");
    occ.bind_lookup(prog.get(), 0); // units 0-2 hold the maps' textures, which the rebuild replaces
    REQUIRE(glGetError() == GL_NO_ERROR);
    occ.build(mesh, light_space::fit(light_spec::directional({0.2f, -1.0f, -0.6f}), s.model.bounds(), 64));
    CHECK(glGetError() == GL_NO_ERROR);
    GLint bound = -1;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    CHECK(bound == 0); // unit 0's range map was replaced: unbound, as GL unbinds a deleted texture
    hostile_engine::reset();
}

TEST_CASE("the raster path's depth extent reduced on the GPU is the range map's, exactly", "[gl][state]") {
    // (The compute path takes it from the segments' ends, as the CPU does: test_gl_compute.cpp.)
    test::gl_context();
    const test_scene s;
    const gl::hair_mesh mesh(s.model);
    gl::light_pass pass(gl::build_path::raster);
    // Tile counts of 1, a partial tile, whole tiles, one more, and many.
    for (int res : {1, 63, 64, 65, 96, 300}) {
        pass.run(mesh, light_space::fit(light_spec::directional({0.2f, -1.0f, -0.6f}), s.model.bounds(), res));
        const auto range = gl::detail::read_range(*pass.textures());
        float nearest = 3e38f, furthest = -3e38f;
        for (std::size_t i = 0; i < std::size_t(res) * std::size_t(res); ++i)
            if (range[4 * i] <= range[4 * i + 3]) nearest = std::min(nearest, range[4 * i]), furthest = std::max(furthest, range[4 * i + 3]);
        const auto extent = gl::detail::extent_in_extra_row(range, res);
        CAPTURE(res, nearest, furthest);
        REQUIRE(nearest < furthest);
        CHECK(extent.nearest == nearest);
        CHECK(extent.furthest == furthest);
    }
    // No segment at all: the extent is zero, as the CPU's extent_of gives.
    const gl::hair_mesh nothing(test::grid_model(4, 1));
    pass.run(nothing, s.light);
    const auto extent = gl::detail::extent_in_extra_row(gl::detail::read_range(*pass.textures()), s.light.resolution());
    CHECK(extent.nearest == 0.0f);
    CHECK(extent.furthest == 0.0f);
}
