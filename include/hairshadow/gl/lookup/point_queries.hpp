#pragma once
/// @file
/// Transmittance at many world points through a method's GLSL look-up: hs_transmittance runs in a
/// vertex shader, one point per vertex, into a shader storage buffer (no rasterisation).

#include <hairshadow/core/error.hpp>
#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/context/state_guard.hpp>

#include <glm/vec3.hpp>

#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// A compiled point-query program for one look-up source (a method's lookup_source()).
class point_queries {
public:
    explicit point_queries(const std::string& lookup_source) {
        static constexpr std::string_view main_text = R"(
layout(location = 0) in vec3 hs_point;
layout(std430, binding = 1) buffer hs_results_buffer { float hs_results[]; };
void main() { hs_results[gl_VertexID] = hs_transmittance(hs_point); gl_Position = vec4(0.0); }
)";
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {lookup_source, main_text}, "point queries");
        program_ = link_program({&vs}, "point queries");
    }

    /// T at each point; `bind(program)` binds the maps (the method's bind_lookup).
    std::vector<float> run(std::span<const glm::vec3> points, const std::function<void(GLuint)>& bind) const {
        std::vector<float> out(points.size());
        if (points.empty()) return out;
        if (points.size() > std::size_t(std::numeric_limits<GLsizei>::max())) throw argument_error("too many points for one GL draw");
        state_guard guard("hairshadow: point queries", state_guard::all_texture_units); // `bind` may bind any unit
        guard.set_pass_state();
        auto positions = make_buffer(), results = make_buffer();
        auto vao = make_vertex_array();
        glBindVertexArray(vao.get());
        glBindBuffer(GL_ARRAY_BUFFER, positions.get());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(points.size_bytes()), points.data(), GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, results.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(out.size() * sizeof(float)), nullptr, GL_DYNAMIC_READ);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, results.get());
        // Nothing is rasterised, but a surfaceless context has no default framebuffer to draw into:
        // an attachment-less one (GL 4.3) is complete.
        auto fbo = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
        glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
        glUseProgram(program_.get());
        bind(program_.get());
        glEnable(GL_RASTERIZER_DISCARD);
        glDrawArrays(GL_POINTS, 0, GLsizei(points.size()));
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
        check("point queries");
        return out;
    }

private:
    gl::program program_;
};

} // namespace hairshadow::gl
