#pragma once
/// @file
/// A hair model on the GPU (positions, thickness and opacity per point, one index pair per segment)
/// and the uniforms of its light-space passes.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/context/state_guard.hpp>
#include <hairshadow/raster/rasterizer.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// Where one per-point attribute lives in a GL buffer that the user owns (a simulation's output, a
/// renderer's vertex buffer): floats from `offset` bytes in, one point every `stride` bytes.
struct buffer_attribute {
    GLuint buffer = 0;     ///< a buffer object's name
    GLintptr offset = 0;   ///< bytes to the first point's value
    GLsizei stride = 0;    ///< bytes from one point's value to the next; 0: tightly packed
};

/// The points of a hair in buffers that the user owns. Thickness and opacity are optional: without a
/// buffer, every point takes the given value (as hair_model's default thickness and transparency).
struct point_buffers {
    std::size_t point_count = 0;
    buffer_attribute positions;                 ///< three floats a point, world space
    std::optional<buffer_attribute> thickness;  ///< one float a point: the strand's world-space width
    std::optional<buffer_attribute> opacity;    ///< one float a point: 1 - transparency
    float uniform_thickness = 0.0f;             ///< every point's thickness without a buffer (> 0)
    float uniform_opacity = 1.0f;               ///< every point's opacity without a buffer (0 to 1)
};

/// Segments of strands that all have the same number of points, stored one strand after the other:
/// points i and i + 1 of each strand.
struct strand_segments {
    std::size_t strand_count = 0;
    std::size_t points_per_strand = 0;
};

/// Segments from an index buffer that the user owns: `segment_count` pairs of GLuint point indices
/// from `offset` bytes in, drawn as GL_LINES in their order. Indices are checked once, when the mesh is
/// made: change them later only to indices below the point count.
struct index_segments {
    GLuint buffer = 0;
    GLintptr offset = 0;
    std::size_t segment_count = 0;
};

/// Vertex and index buffers of a hair model, drawn as GL_LINES: the library's own copy of a
/// hair_model (update() moves its points in place), or a view of buffers the user owns (a GPU
/// simulation writes them, and the next build sees the new positions with no copy).
class hair_mesh {
public:
    /// Uploads `model`: positions first, then thickness and opacity, so that update() writes one range.
    explicit hair_mesh(const hair_model& model) : vao_(make_vertex_array()), vertices_(make_buffer()), indices_(make_buffer()) {
        const std::size_t n = model.point_count();
        std::vector<float> v(5 * n);
        for (std::size_t i = 0; i < n; ++i) {
            const auto& p = model.points[i];
            v[3 * i] = p.x, v[3 * i + 1] = p.y, v[3 * i + 2] = p.z;
            v[3 * n + i] = model.thickness_at(i);
            v[4 * n + i] = 1.0f - model.transparency_at(i);
        }
        std::vector<std::uint32_t> e;
        e.reserve(model.segment_count() * 2);
        for (std::size_t s = 0; s < model.strand_count(); ++s)
            for (std::uint32_t i = model.strand_offsets[s]; i + 1 < model.strand_offsets[s + 1]; ++i) e.insert(e.end(), {i, i + 1});
        point_count_ = n;
        owns_points_ = true;
        uniform_attributes_ = model.thickness.empty() && model.transparency.empty();
        state_guard guard("hairshadow: hair mesh upload"); // the caller's vertex array and array buffer stay bound
        glBindVertexArray(vao_.get());
        upload(GL_ARRAY_BUFFER, vertices_.get(), v.size() * sizeof(float), v.data());
        const auto at = [&](std::size_t floats) { return buffer_attribute{vertices_.get(), GLintptr(floats * sizeof(float)), 0}; };
        point_attribute(0, 3, at(0));
        point_attribute(1, 1, at(3 * n));
        point_attribute(2, 1, at(4 * n));
        sources_.points = {n, at(0), at(3 * n), at(4 * n)};
        index_range(e);
        glBindVertexArray(0);
        check("hair_mesh upload");
    }

    /// A view of the user's buffers, segments by strands of a fixed point count (the library makes the
    /// index buffer). The buffers must outlive the mesh; throws argument_error for a layout that does not
    /// fit the buffers' sizes, a stride above 2048 bytes (GL 4.4's least maximum), or a count of points
    /// the strands do not match.
    hair_mesh(const point_buffers& points, strand_segments strands) : vao_(make_vertex_array()), vertices_(make_buffer()), indices_(make_buffer()) {
        if (strands.points_per_strand < 2 || strands.strand_count == 0 ||
            strands.strand_count > points.point_count / strands.points_per_strand ||
            strands.strand_count * strands.points_per_strand != points.point_count)
            throw argument_error("hair_mesh: " + std::to_string(strands.strand_count) + " strands of " + std::to_string(strands.points_per_strand) +
                                 " points do not make the " + std::to_string(points.point_count) + " points given");
        if (2 * (points.point_count - strands.strand_count) > std::size_t(std::numeric_limits<GLsizei>::max()))
            throw argument_error("hair_mesh: more segments than one draw holds"); // before making their indices
        state_guard guard("hairshadow: hair mesh over user buffers");
        view_points(points);
        std::vector<std::uint32_t> e;
        e.reserve(strands.strand_count * (strands.points_per_strand - 1) * 2);
        for (std::size_t s = 0; s < strands.strand_count; ++s)
            for (std::size_t i = 0; i + 1 < strands.points_per_strand; ++i) {
                const auto first = std::uint32_t(s * strands.points_per_strand + i);
                e.insert(e.end(), {first, first + 1});
            }
        index_range(e);
        glBindVertexArray(0);
        check("hair_mesh over user buffers");
    }

    /// A view of the user's buffers, segments from the user's index buffer. Reads the indices back once
    /// to check that each is below the point count (an index past the buffer would read any memory).
    hair_mesh(const point_buffers& points, index_segments segments) : vao_(make_vertex_array()), vertices_(make_buffer()), indices_(make_buffer()) {
        if (segments.segment_count > std::size_t(std::numeric_limits<GLsizei>::max() / 2))
            throw argument_error("hair_mesh: " + std::to_string(segments.segment_count) + " segments are more than one draw holds");
        state_guard guard("hairshadow: hair mesh over user buffers");
        const std::size_t index_bytes = segments.segment_count * 2 * sizeof(std::uint32_t);
        check_fits(segments.buffer, segments.offset, segments.segment_count == 0 ? 0 : index_bytes, 0, 1, "the index buffer");
        std::vector<std::uint32_t> e(segments.segment_count * 2);
        if (!e.empty()) {
            glBindBuffer(GL_ARRAY_BUFFER, segments.buffer);
            glGetBufferSubData(GL_ARRAY_BUFFER, segments.offset, GLsizeiptr(index_bytes), e.data());
        }
        for (const std::uint32_t i : e)
            if (i >= points.point_count)
                throw argument_error("hair_mesh: index " + std::to_string(i) + " is past the " + std::to_string(points.point_count) + " points");
        view_points(points);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, segments.buffer);
        index_offset_ = segments.offset;
        sources_.index_buffer = segments.buffer;
        sources_.index_offset = segments.offset;
        index_count_ = GLsizei(e.size());
        glBindVertexArray(0);
        check("hair_mesh over user buffers");
    }

    /// Moves the points of a mesh made from a hair_model, in place and with no new storage: the next
    /// build sees them. Thickness and opacity stay. Throws argument_error for a point count other than
    /// the mesh's, and for a mesh over the user's buffers (write those buffers instead).
    void update(std::span<const glm::vec3> points) {
        if (!owns_points_) throw argument_error("hair_mesh::update: this mesh reads the user's buffers; write the positions there");
        if (points.size() != point_count_)
            throw argument_error("hair_mesh::update: " + std::to_string(points.size()) + " points for a mesh of " + std::to_string(point_count_));
        if (points.empty()) return;
        state_guard guard("hairshadow: hair mesh update");
        glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
        static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "positions are packed as three floats");
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(points.size() * sizeof(glm::vec3)), points.data());
        check("hair_mesh::update");
    }

    /// Draws every segment; gl_PrimitiveID is the segment's index. Leaves the mesh's vertex array
    /// bound: the library calls it within a state_guard.
    void draw() const {
        glBindVertexArray(vao_.get());
        glDrawElements(GL_LINES, index_count_, GL_UNSIGNED_INT, reinterpret_cast<const void*>(index_offset_));
    }

    std::size_t point_count() const noexcept { return point_count_; }
    std::size_t segment_count() const noexcept { return std::size_t(index_count_) / 2; }
    /// Every point has the same thickness and opacity (a model without per-point values, or buffers
    /// without thickness and opacity buffers): with a footprint that does not vary, every segment has
    /// one alpha, and the compute build works out each segment's optical depth once.
    bool uniform_attributes() const noexcept { return uniform_attributes_; }

    /// Where the mesh's data lives, for passes that read buffers rather than draw (the compute
    /// build): the points' buffers, and two uint32 indices per segment from `index_offset` bytes into
    /// `index_buffer`.
    struct buffer_sources {
        point_buffers points;
        GLuint index_buffer = 0;
        GLintptr index_offset = 0;
    };
    const buffer_sources& sources() const noexcept { return sources_; }

private:
    static void upload(GLenum target, GLuint name, std::size_t bytes, const void* data) {
        glBindBuffer(target, name);
        glBufferData(target, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    }

    /// The library's index buffer, bound to the vertex array.
    void index_range(const std::vector<std::uint32_t>& e) {
        if (e.size() > std::size_t(std::numeric_limits<GLsizei>::max())) throw argument_error("hair_mesh: more segments than one draw holds");
        upload(GL_ELEMENT_ARRAY_BUFFER, indices_.get(), e.size() * sizeof(std::uint32_t), e.data());
        index_count_ = GLsizei(e.size());
        sources_.index_buffer = indices_.get();
        sources_.index_offset = 0;
    }

    /// Throws unless `name` is a buffer holding `count` values of `value_bytes` from `offset`, `stride` apart.
    static void check_fits(GLuint name, GLintptr offset, std::size_t value_bytes, GLsizei stride, std::size_t count, const std::string& what) {
        if (name == 0 || !glIsBuffer(name)) throw argument_error("hair_mesh: " + what + " is not a buffer object");
        if (offset < 0 || stride < 0 || stride > 2048 || offset % 4 != 0 || stride % 4 != 0)
            throw argument_error("hair_mesh: " + what + " needs an offset of 0 or more and a stride of 0 to 2048 bytes, both multiples of 4");
        glBindBuffer(GL_ARRAY_BUFFER, name);
        GLint64 size = 0;
        glGetBufferParameteri64v(GL_ARRAY_BUFFER, GL_BUFFER_SIZE, &size);
        const std::size_t step = stride == 0 ? value_bytes : std::size_t(stride);
        // Within the buffer: offset + (count - 1) x step + value_bytes <= size, without overflow.
        if (count == 0) return;
        const std::size_t room = std::size_t(std::max<GLint64>(size, 0));
        if (std::size_t(offset) > room || value_bytes > room - std::size_t(offset) ||
            (count > 1 && (room - std::size_t(offset) - value_bytes) / step < count - 1))
            throw argument_error("hair_mesh: " + what + " of " + std::to_string(size) + " bytes does not hold " + std::to_string(count) +
                                 " values from byte " + std::to_string(offset) + ", " + std::to_string(step) + " apart");
    }

    /// Points the vertex array's attribute at a user's buffer.
    void point_attribute(GLuint index, GLint floats, const buffer_attribute& a) {
        glBindBuffer(GL_ARRAY_BUFFER, a.buffer);
        glEnableVertexAttribArray(index);
        glVertexAttribPointer(index, floats, GL_FLOAT, GL_FALSE, a.stride, reinterpret_cast<const void*>(a.offset));
        glVertexAttribDivisor(index, 0);
    }

    /// Checks and binds the user's point buffers; an attribute without a buffer reads one value of the
    /// library's, through an instance divisor (every vertex of a draw of one instance reads element 0).
    void view_points(const point_buffers& points) {
        if (points.point_count > std::numeric_limits<std::uint32_t>::max()) throw argument_error("hair_mesh: more than 2^32 - 1 points");
        const auto n = points.point_count;
        check_fits(points.positions.buffer, points.positions.offset, 3 * sizeof(float), points.positions.stride, n, "the position buffer");
        if (points.thickness) check_fits(points.thickness->buffer, points.thickness->offset, sizeof(float), points.thickness->stride, n, "the thickness buffer");
        else if (!(points.uniform_thickness > 0.0f) || !std::isfinite(points.uniform_thickness))
            throw argument_error("hair_mesh: without a thickness buffer, uniform_thickness must be positive and finite");
        if (points.opacity) check_fits(points.opacity->buffer, points.opacity->offset, sizeof(float), points.opacity->stride, n, "the opacity buffer");
        else if (!(points.uniform_opacity >= 0.0f && points.uniform_opacity <= 1.0f))
            throw argument_error("hair_mesh: without an opacity buffer, uniform_opacity must be 0 to 1");
        point_count_ = n;
        uniform_attributes_ = !points.thickness && !points.opacity;
        sources_.points = points;
        const float constants[2] = {points.uniform_thickness, points.uniform_opacity};
        glBindVertexArray(vao_.get());
        upload(GL_ARRAY_BUFFER, vertices_.get(), sizeof constants, constants);
        point_attribute(0, 3, points.positions);
        const buffer_attribute constant_thickness{vertices_.get(), 0, 0}, constant_opacity{vertices_.get(), sizeof(float), 0};
        point_attribute(1, 1, points.thickness.value_or(constant_thickness));
        if (!points.thickness) glVertexAttribDivisor(1, 1);
        point_attribute(2, 1, points.opacity.value_or(constant_opacity));
        if (!points.opacity) glVertexAttribDivisor(2, 1);
    }

    vertex_array vao_;
    buffer vertices_, indices_;
    GLsizei index_count_ = 0;
    GLintptr index_offset_ = 0;
    std::size_t point_count_ = 0;
    bool owns_points_ = false;
    bool uniform_attributes_ = false;
    buffer_sources sources_;
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
