#pragma once
// One OSMesa core 4.5 context for all GL tests of the executable, current and loaded.
#include <glad/gl.h>

#include <hairshadow/gl/osmesa_context.hpp>

#include <catch2/catch.hpp>

namespace test {
inline hairshadow::gl::osmesa_context& gl_context() {
    static hairshadow::gl::osmesa_context ctx(4, 5);
    static const bool loaded = gladLoadGL(ctx.loader()) != 0;
    REQUIRE(loaded);
    ctx.make_current();
    return ctx;
}
} // namespace test

#include <hairshadow/gl/objects.hpp>
#include <hairshadow/hairshadow.hpp>

#include <glm/matrix.hpp>

#include <functional>
#include <string>
#include <vector>

namespace test {

/// Points well inside their texels: the centres of every `step`-th occupied texel, at depths from just
/// in front of its nearest fragment to just behind its furthest.
inline std::vector<glm::vec3> texel_centre_queries(const hairshadow::fragment_buffer& fragments, const hairshadow::light_space& light, int step) {
    std::vector<glm::vec3> queries;
    const glm::mat4 to_world = glm::inverse(light.view_projection());
    const int res = light.resolution();
    for (int y = 1; y < res; y += step)
        for (int x = 1; x < res; x += step) {
            const auto frags = fragments.texel(x, y);
            if (frags.empty()) continue;
            float lo = frags[0].depth, hi = lo;
            for (const auto& f : frags) lo = std::min(lo, f.depth), hi = std::max(hi, f.depth);
            for (float f : {-0.001f, 0.25f, 0.5f, 0.75f, 1.001f}) {
                const float depth = lo + f * (hi - lo);
                const glm::vec4 ndc((float(x) + 0.5f) / float(res) * 2.0f - 1.0f, (float(y) + 0.5f) / float(res) * 2.0f - 1.0f, 2.0f * depth - 1.0f, 1.0f);
                const glm::vec4 w = to_world * ndc;
                queries.push_back(glm::vec3(w) / w.w);
            }
        }
    return queries;
}

/// Runs hs_transmittance(point) in a vertex shader over `points`; `bind` sets the maps' uniforms.
inline std::vector<float> gl_lookup(const std::string& lookup_source, const std::function<void(GLuint)>& bind, const std::vector<glm::vec3>& points) {
    namespace gl = hairshadow::gl;
    const std::string main_text = R"(
layout(location = 0) in vec3 hs_point;
layout(std430, binding = 1) buffer hs_results_buffer { float hs_results[]; };
void main() { hs_results[gl_VertexID] = hs_transmittance(hs_point); gl_Position = vec4(0.0); }
)";
    const auto vs = gl::compile_shader(GL_VERTEX_SHADER, {"#version 430 core\n", lookup_source, main_text}, "look-up test");
    const auto program = gl::link_program({&vs}, "look-up test");
    auto buffer = gl::make_buffer(), results = gl::make_buffer();
    auto vao = gl::make_vertex_array();
    glBindVertexArray(vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, buffer.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(points.size() * sizeof(glm::vec3)), points.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, results.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(points.size() * sizeof(float)), nullptr, GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, results.get());
    glUseProgram(program.get());
    bind(program.get());
    glEnable(GL_RASTERIZER_DISCARD);
    glDrawArrays(GL_POINTS, 0, GLsizei(points.size()));
    glDisable(GL_RASTERIZER_DISCARD);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> out(points.size());
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
    glBindVertexArray(0);
    gl::check("look-up");
    return out;
}

} // namespace test
