// gl::hair_mesh over buffers the user owns (a stride, an offset, optional thickness and opacity, strands
// or an index buffer) gives the maps of the mesh made from the same hair_model; update() in place gives
// the maps of a fresh mesh; layouts that do not fit their buffers are refused.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/procedural/motion.hpp>

#include <cstring>

using namespace hairshadow;

namespace {

/// A vertex as a renderer might store it: position, a normal the maps never read, thickness, opacity.
struct engine_vertex {
    glm::vec3 normal;
    glm::vec3 position;
    float thickness;
    float opacity;
};

hair_model test_hair() {
    return make_procedural({.style = hair_style::wavy, .strands = 600, .segments = 20, .seed = 5}); // every strand 21 points
}

template <class Maps>
auto maps_of(const gl::hair_mesh& mesh, const light_space& light) {
    Maps maps;
    maps.build(mesh, light);
    return maps.read_back();
}

template <class Texels>
long differing(const Texels& a, const Texels& b) {
    REQUIRE(a.size() == b.size());
    long n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(a[i])) != 0;
    return n;
}

/// The user's buffer: 64 bytes of header, then one engine_vertex a point.
gl::buffer engine_buffer(const hair_model& model, float opacity_scale = 1.0f) {
    std::vector<std::uint8_t> bytes(64 + model.point_count() * sizeof(engine_vertex), 0xAB);
    for (std::size_t i = 0; i < model.point_count(); ++i) {
        const engine_vertex v{{0, 0, 1}, model.points[i], model.thickness_at(i), opacity_scale * (1.0f - model.transparency_at(i))};
        std::memcpy(bytes.data() + 64 + i * sizeof(engine_vertex), &v, sizeof v);
    }
    gl::buffer b = gl::make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, b.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes.size()), bytes.data(), GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return b;
}

gl::point_buffers engine_points(const hair_model& model, GLuint buffer) {
    constexpr auto stride = GLsizei(sizeof(engine_vertex));
    gl::point_buffers p;
    p.point_count = model.point_count();
    p.positions = {buffer, GLintptr(64 + offsetof(engine_vertex, position)), stride};
    p.thickness = gl::buffer_attribute{buffer, GLintptr(64 + offsetof(engine_vertex, thickness)), stride};
    p.opacity = gl::buffer_attribute{buffer, GLintptr(64 + offsetof(engine_vertex, opacity)), stride};
    return p;
}

} // namespace

TEMPLATE_TEST_CASE("maps from the user's strided buffers equal maps from the model", "[gl][motion]", gl::maps<deep_opacity_maps<3>>,
                   (gl::maps<occupancy_maps<128, 4>>), gl::maps<density_clustering<4>>) {
    test::gl_context();
    const hair_model model = test_hair();
    const auto light = light_space::fit(light_spec::directional({0.6f, -1, 0.6f}), model.bounds(), 128);
    const auto expected = maps_of<TestType>(gl::hair_mesh(model), light);
    const gl::buffer user = engine_buffer(model);
    const gl::point_buffers points = engine_points(model, user.get());

    SECTION("strands of a fixed point count") {
        const gl::hair_mesh mesh(points, gl::strand_segments{model.strand_count(), model.strand_size(0)});
        CHECK(mesh.segment_count() == model.segment_count());
        CHECK(differing(maps_of<TestType>(mesh, light), expected) == 0);
    }
    SECTION("the user's index buffer, past an offset") {
        std::vector<std::uint32_t> indices{7, 7, 7, 7}; // 16 bytes the mesh skips
        for (std::size_t s = 0; s < model.strand_count(); ++s)
            for (std::uint32_t i = model.strand_offsets[s]; i + 1 < model.strand_offsets[s + 1]; ++i) indices.insert(indices.end(), {i, i + 1});
        gl::buffer index_buffer = gl::make_buffer();
        glBindBuffer(GL_ARRAY_BUFFER, index_buffer.get());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(indices.size() * 4), indices.data(), GL_STATIC_DRAW);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        const gl::hair_mesh mesh(points, gl::index_segments{index_buffer.get(), 16, model.segment_count()});
        CHECK(differing(maps_of<TestType>(mesh, light), expected) == 0);
    }
    SECTION("a GPU write to the user's buffer reaches the next build") {
        const gl::hair_mesh mesh(points, gl::strand_segments{model.strand_count(), model.strand_size(0)});
        const hair_model moved = sway_motion(model, {.amplitude_degrees = 30.0f}).pose(0.5f);
        gl::buffer staging = engine_buffer(moved);
        glBindBuffer(GL_COPY_READ_BUFFER, staging.get());
        glBindBuffer(GL_COPY_WRITE_BUFFER, user.get());
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, GLsizeiptr(64 + model.point_count() * sizeof(engine_vertex)));
        const auto after = maps_of<TestType>(mesh, light);
        CHECK(differing(after, expected) > 100);
        CHECK(differing(after, maps_of<TestType>(gl::hair_mesh(moved), light)) == 0);
    }
}

TEST_CASE("a mesh without thickness or opacity buffers takes the uniform values", "[gl][motion]") {
    test::gl_context();
    hair_model model = test_hair();
    model.default_thickness = 0.002f;
    model.default_transparency = 0.25f;
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 128);
    const gl::buffer user = engine_buffer(model);
    gl::point_buffers points = engine_points(model, user.get());
    points.uniform_thickness = 0.002f;
    points.uniform_opacity = 0.75f;
    CHECK_FALSE(gl::hair_mesh(points, gl::strand_segments{model.strand_count(), model.strand_size(0)}).uniform_attributes());
    points.thickness.reset();
    CHECK_FALSE(gl::hair_mesh(points, gl::strand_segments{model.strand_count(), model.strand_size(0)}).uniform_attributes()); // opacity varies
    points.opacity.reset();
    const gl::hair_mesh mesh(points, gl::strand_segments{model.strand_count(), model.strand_size(0)});
    CHECK(mesh.uniform_attributes()); // every segment has one alpha: the compute build's HS_ONE_ALPHA form
    using maps = gl::maps<opacity_shadow_maps<16>>;
    CHECK(differing(maps_of<maps>(mesh, light), maps_of<maps>(gl::hair_mesh(model), light)) == 0);
}

TEMPLATE_TEST_CASE("update in place gives the maps of a fresh mesh, frame after frame", "[gl][motion]", gl::maps<deep_opacity_maps<3>>,
                   (gl::maps<occupancy_maps<128, 4>>)) {
    test::gl_context();
    const sway_motion sway(test_hair(), {.amplitude_degrees = 30.0f});
    gl::hair_mesh mesh(sway.rest());
    TestType reused;
    hair_model moving;
    const auto box = sway.rest().bounds().expanded(0.3f);
    for (float t : {0.2f, 0.6f, 1.0f}) {
        sway.pose(t, moving);
        mesh.update(moving.points);
        const auto light = light_space::fit(orbit_light(light_spec::directional({0.6f, -1, 0.6f}), t, 3.0f), box, 128);
        reused.build(mesh, light);
        CHECK(differing(reused.read_back(), maps_of<TestType>(gl::hair_mesh(moving), light)) == 0);
    }
}

TEST_CASE("user buffers that do not fit their layout are refused", "[gl][hostile]") {
    test::gl_context();
    const hair_model model = test_hair();
    const gl::buffer user = engine_buffer(model);
    const gl::point_buffers good = engine_points(model, user.get());
    const gl::strand_segments strands{model.strand_count(), model.strand_size(0)};
    auto too_many = good;
    too_many.point_count += model.strand_size(0); // one strand more than the buffer holds
    CHECK_THROWS_AS(gl::hair_mesh(too_many, gl::strand_segments{model.strand_count() + 1, model.strand_size(0)}), argument_error);
    auto not_a_buffer = good;
    not_a_buffer.positions.buffer = 987654;
    CHECK_THROWS_AS(gl::hair_mesh(not_a_buffer, strands), argument_error);
    auto huge_stride = good;
    huge_stride.positions.stride = 4096;
    CHECK_THROWS_AS(gl::hair_mesh(huge_stride, strands), argument_error);
    auto no_thickness = good;
    no_thickness.thickness.reset();
    CHECK_THROWS_AS(gl::hair_mesh(no_thickness, strands), argument_error); // uniform_thickness is 0
    CHECK_THROWS_AS(gl::hair_mesh(good, gl::strand_segments{model.strand_count(), 7}), argument_error);
    // An index past the points.
    const std::uint32_t bad[2] = {0, std::uint32_t(model.point_count())};
    gl::buffer index_buffer = gl::make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, index_buffer.get());
    glBufferData(GL_ARRAY_BUFFER, sizeof bad, bad, GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    CHECK_THROWS_AS(gl::hair_mesh(good, gl::index_segments{index_buffer.get(), 0, 1}), argument_error);
    CHECK_THROWS_AS(gl::hair_mesh(good, gl::index_segments{index_buffer.get(), 0, 2}), argument_error); // past the buffer's end
    // update() belongs to meshes made from a model, with their point count.
    gl::hair_mesh view(good, strands);
    CHECK_THROWS_AS(view.update(model.points), argument_error);
    gl::hair_mesh own(model);
    CHECK_THROWS_AS(own.update(std::span(model.points).first(10)), argument_error);
    CHECK(glGetError() == GL_NO_ERROR);
}
