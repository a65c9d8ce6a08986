#pragma once
/// @file
/// Captures the fragments GL rasterises, as a CPU fragment_buffer (segment order within each texel),
/// so that GL maps can be checked against CPU maps built from exactly the same fragments: GL
/// implementations decide line ends and interpolate depth in their own ways (see tests/gl).

#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/raster/fragment.hpp>

#include <algorithm>
#include <array>
#include <cstring>

namespace hairshadow::gl {

/// Every fragment of `mesh` in `light`'s map, as GL rasterises it with `options`' alpha.
inline fragment_buffer capture_fragments(const hair_mesh& mesh, const light_space& light, const raster_options& options) {
    const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
    const auto fs = compile_stage(GL_FRAGMENT_SHADER, {}, {"#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n",
                                    shaders::raster_coverage, shaders::passes_capture},
                                   "passes/capture");
    const auto prog = link_program({&vs, &fs}, "fragment capture");
    const int res = light.resolution();
    auto fbo = make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, res);
    glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, res);
    glViewport(0, 0, res, res);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(prog.get());
    set_light_uniforms(prog.get(), light, options);
    glUniform1i(glGetUniformLocation(prog.get(), "hs_resolution"), res);
    std::size_t capacity = 1u << 20;
    std::vector<std::array<std::uint32_t, 4>> records;
    for (int attempt = 0; attempt < 2; ++attempt) {
        auto ssbo = make_buffer();
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, ssbo.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(16 * (capacity + 1)), nullptr, GL_DYNAMIC_READ);
        const std::uint32_t zero[4] = {0, 0, 0, 0};
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, 16, zero);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, ssbo.get());
        mesh.draw();
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::uint32_t count = 0;
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, 4, &count);
        if (count <= capacity) {
            records.resize(count);
            if (count) glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 16, GLsizeiptr(16 * std::size_t(count)), records.data());
            break;
        }
        capacity = count; // too small: draw again with room for every fragment
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    check("fragment capture");
    // Texel by texel, in segment order, as the CPU rasteriser stores them.
    std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a[0] != b[0] ? a[0] < b[0] : a[3] < b[3]; });
    std::vector<std::uint64_t> offsets(std::size_t(res) * std::size_t(res) + 1, 0);
    std::vector<fragment> fragments(records.size());
    for (std::size_t i = 0; i < records.size(); ++i) {
        ++offsets[records[i][0] + 1];
        std::memcpy(&fragments[i].depth, &records[i][1], 4);
        std::memcpy(&fragments[i].alpha, &records[i][2], 4);
    }
    for (std::size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
    return fragment_buffer(res, std::move(offsets), std::move(fragments));
}

} // namespace hairshadow::gl
