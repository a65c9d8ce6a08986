// Occupancy maps on GL against the CPU kernel, both built from the fragments GL rasterised.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/fragment_capture.hpp>
#include <hairshadow/gl/occupancy_maps.hpp>
#include <hairshadow/hairshadow.hpp>

#include <glm/matrix.hpp>

#include "../test_support.hpp"

using namespace hairshadow;

namespace {

template <int S, int B>
void check_occupancy(const hair_model& model, const light_space& light) {
    CAPTURE(S, B);
    test::gl_context();
    const gl::hair_mesh mesh(model);
    const raster_options options;
    const fragment_buffer fragments = gl::capture_fragments(mesh, light, options);
    REQUIRE(fragments.size() > 10000);
    occupancy_maps<S, B> cpu;
    cpu.build(fragments, light);
    gl::occupancy_maps_gl<S, B> on_gl;
    on_gl.build(mesh, light, options);
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long range_off = 0, bits_off = 0, slabs_off = 0, occupied = 0;
    float worst_slab = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            occupied += !fragments.texel(x, y).empty();
            range_off += c.placement.nearest != g.placement.nearest || c.placement.furthest != g.placement.furthest;
            bits_off += c.data.bits != g.data.bits;
            for (int s = 0; s < B; ++s) {
                const float a = c.data.slabs[std::size_t(s)], b = g.data.slabs[std::size_t(s)];
                const float error = std::abs(a - b) / std::max(std::abs(a), 1e-3f);
                worst_slab = std::max(worst_slab, error);
                slabs_off += error > 1e-5f;
            }
        }
    CAPTURE(worst_slab);
    CHECK(occupied > 1000);
    CHECK(range_off == 0); // MIN / MAX blending: bit-exact
    CHECK(bits_off == 0);  // OR-ed occupancy bits: bit-exact
    CHECK(slabs_off == 0); // additive float sums: within 1e-5 relative

    // The GLSL look-up equals the CPU query at points well inside their texels (texel centres, at
    // depths through each texel's hair); at the model's own points it agrees but where a point lies
    // within float rounding of a texel edge, and the two sides may pick neighbouring texels.
    std::vector<glm::vec3> queries;
    const glm::mat4 to_world = glm::inverse(light.view_projection());
    for (int y = 1; y < res; y += 5)
        for (int x = 1; x < res; x += 5) {
            const auto frags = fragments.texel(x, y);
            if (frags.empty()) continue;
            for (float f : {-0.001f, 0.25f, 0.5f, 0.75f, 1.001f}) {
                const float lo = cpu.texel(x, y).placement.nearest, hi = cpu.texel(x, y).placement.furthest;
                const float depth = lo + f * (hi - lo);
                const glm::vec4 ndc((float(x) + 0.5f) / float(res) * 2.0f - 1.0f, (float(y) + 0.5f) / float(res) * 2.0f - 1.0f, 2.0f * depth - 1.0f, 1.0f);
                const glm::vec4 w = to_world * ndc;
                queries.push_back(glm::vec3(w) / w.w);
            }
        }
    const std::size_t query_count = queries.size();
    queries.insert(queries.end(), model.points.begin(), model.points.end());
    const std::string main_text = R"(
layout(location = 0) in vec3 hs_point;
layout(std430, binding = 1) buffer hs_results_buffer { float hs_results[]; };
void main() { hs_results[gl_VertexID] = hs_transmittance(hs_point); gl_Position = vec4(0.0); }
)";
    const auto vs = gl::compile_shader(GL_VERTEX_SHADER, {"#version 430 core\n", gl::occupancy_maps_gl<S, B>::lookup_source(), main_text},
                                       "look-up test");
    const auto program = gl::link_program({&vs}, "look-up test");
    auto points = gl::make_buffer(), results = gl::make_buffer();
    auto vao = gl::make_vertex_array();
    glBindVertexArray(vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, points.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(queries.size() * sizeof(glm::vec3)), queries.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, results.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(queries.size() * sizeof(float)), nullptr, GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, results.get());
    glUseProgram(program.get());
    on_gl.bind_lookup(program.get());
    glEnable(GL_RASTERIZER_DISCARD);
    glDrawArrays(GL_POINTS, 0, GLsizei(queries.size()));
    glDisable(GL_RASTERIZER_DISCARD);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> on_gpu(queries.size());
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(on_gpu.size() * sizeof(float)), on_gpu.data());
    glBindVertexArray(0);
    gl::check("look-up");
    std::vector<float> on_cpu(queries.size());
    cpu.transmittance(queries, on_cpu);
    float worst = 0;
    int shadowed = 0;
    for (std::size_t i = 0; i < query_count; ++i) {
        worst = std::max(worst, std::abs(on_gpu[i] - on_cpu[i]));
        shadowed += on_cpu[i] < 0.9f;
    }
    std::size_t model_off = 0;
    for (std::size_t i = query_count; i < queries.size(); ++i) model_off += std::abs(on_gpu[i] - on_cpu[i]) > 1e-5f;
    CAPTURE(worst, query_count, model_off);
    CHECK(query_count >= 1000);
    CHECK(shadowed > 500);
    CHECK(worst < 1e-5f);
    CHECK(model_off * 200 < model.point_count()); // under 0.5% of the model's points, all at texel edges
}

} // namespace

TEST_CASE("GL occupancy maps equal the CPU maps, and the GLSL look-up the CPU query", "[gl][occ]") {
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    check_occupancy<128, 4>(model, light);
    check_occupancy<256, 8>(model, light);
    check_occupancy<32, 1>(model, light);
}
