#pragma once
/// @file
/// A hair model on the GPU (positions, thickness and opacity per point, one index pair per segment)
/// and the uniforms of its light-space passes.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/gl/objects.hpp>
#include <hairshadow/gl/state_guard.hpp>
#include <hairshadow/raster/rasterizer.hpp>

#include <vector>

namespace hairshadow::gl {

/// Vertex and index buffers of a hair model, drawn as GL_LINES.
class hair_mesh {
public:
    explicit hair_mesh(const hair_model& model) : vao_(make_vertex_array()), vertices_(make_buffer()), indices_(make_buffer()) {
        std::vector<float> v;
        v.reserve(model.point_count() * 5);
        for (std::size_t i = 0; i < model.point_count(); ++i) {
            const auto& p = model.points[i];
            v.insert(v.end(), {p.x, p.y, p.z, model.thickness_at(i), 1.0f - model.transparency_at(i)});
        }
        std::vector<std::uint32_t> e;
        e.reserve(model.segment_count() * 2);
        for (std::size_t s = 0; s < model.strand_count(); ++s)
            for (std::uint32_t i = model.strand_offsets[s]; i + 1 < model.strand_offsets[s + 1]; ++i) e.insert(e.end(), {i, i + 1});
        index_count_ = GLsizei(e.size());
        state_guard guard("hairshadow: hair mesh upload"); // the caller's vertex array and array buffer stay bound
        glBindVertexArray(vao_.get());
        glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
        constexpr GLsizei stride = 5 * sizeof(float);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
        glEnableVertexAttribArray(1);
        glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(3 * sizeof(float)));
        glEnableVertexAttribArray(2);
        glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(4 * sizeof(float)));
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(e.size() * sizeof(std::uint32_t)), e.data(), GL_STATIC_DRAW);
        glBindVertexArray(0);
        check("hair_mesh upload");
    }

    /// Draws every segment; gl_PrimitiveID is the segment's index. Leaves the mesh's vertex array
    /// bound: the library calls it within a state_guard.
    void draw() const {
        glBindVertexArray(vao_.get());
        glDrawElements(GL_LINES, index_count_, GL_UNSIGNED_INT, nullptr);
    }

private:
    vertex_array vao_;
    buffer vertices_, indices_;
    GLsizei index_count_ = 0;
};

/// Sets the uniforms of raster/vertex.glsl and raster/coverage.glsl on the current program.
inline void set_light_uniforms(GLuint prog, const light_space& light, const raster_options& options) {
    glUniformMatrix4fv(glGetUniformLocation(prog, "hs_view_projection"), 1, GL_FALSE, &light.view_projection()[0][0]);
    glUniformMatrix4fv(glGetUniformLocation(prog, "hs_view"), 1, GL_FALSE, &light.view()[0][0]);
    glUniform1f(glGetUniformLocation(prog, "hs_near"), light.near_plane());
    glUniform1f(glGetUniformLocation(prog, "hs_far"), light.far_plane());
    glUniform1i(glGetUniformLocation(prog, "hs_use_fixed_alpha"), options.fixed_alpha ? 1 : 0);
    glUniform1f(glGetUniformLocation(prog, "hs_fixed_alpha"), options.fixed_alpha.value_or(0.0f));
    glUniform2f(glGetUniformLocation(prog, "hs_texel_size"), light.texel_size(0.0f), light.texel_size(1.0f) - light.texel_size(0.0f));
    glUniform1i(glGetUniformLocation(prog, "hs_depth_weighting"), options.depth_weighting ? 1 : 0);
}

} // namespace hairshadow::gl
