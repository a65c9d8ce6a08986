#pragma once
/// @file
/// The pre-pass every GL method starts with: each texel's nearest fragment under MIN blending (red)
/// and furthest under MAX blending (alpha), read back once for the per-texel states and the map's
/// global depth extent. Also the look-up's light uniforms, shared by every method's hs_transmittance.

#include <hairshadow/gl/hair_mesh.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <string>
#include <vector>

namespace hairshadow::gl {

/// The depth-range map of a hair mesh.
class depth_range_pass {
public:
    depth_range_pass() {
        const auto vs = compile_shader(GL_VERTEX_SHADER, {"#version 430 core\n", shaders::raster_vertex}, "raster/vertex");
        const auto fs = compile_shader(GL_FRAGMENT_SHADER,
                                       {"#version 430 core\n", "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n",
                                        shaders::raster_coverage, shaders::passes_depth_range},
                                       "passes/depth_range");
        program_ = link_program({&vs, &fs}, "depth-range pass");
    }

    /// Draws the range map of `mesh` seen from `light` and reads it back.
    void run(const hair_mesh& mesh, const light_space& light, const raster_options& options) {
        const int res = light.resolution();
        if (res != resolution_) {
            map_ = make_texture();
            glBindTexture(GL_TEXTURE_2D, map_.get());
            glTexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, res, res);
            resolution_ = res;
        }
        auto fbo = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, map_.get(), 0);
        const GLenum first = GL_COLOR_ATTACHMENT0;
        glDrawBuffers(1, &first);
        glViewport(0, 0, res, res);
        glDisable(GL_DEPTH_TEST);
        const float clear[4] = {3.0e38f, 0.0f, 0.0f, -3.0e38f};
        glClearBufferfv(GL_COLOR, 0, clear);
        glEnable(GL_BLEND);
        glBlendEquationSeparate(GL_MIN, GL_MAX);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(program_.get());
        set_light_uniforms(program_.get(), light, options);
        mesh.draw();
        glDisable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        values_.resize(4 * std::size_t(res) * std::size_t(res));
        glBindTexture(GL_TEXTURE_2D, map_.get());
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, values_.data());
        check("depth-range pass");
    }

    const texture& map() const noexcept { return map_; }
    /// Texel i's range: [0] nearest, [3] furthest.
    const float* texel(std::size_t i) const noexcept { return &values_[4 * i]; }
    /// True when no fragment fell in texel i.
    bool empty(std::size_t i) const noexcept { return values_[4 * i] > values_[4 * i + 3]; }
    /// Nearest and furthest fragment of the whole map; {0, 0} when it is empty.
    depth_extent extent() const noexcept {
        depth_extent e{3.0e38f, -3.0e38f};
        for (std::size_t i = 0; i < values_.size(); i += 4)
            if (values_[i] <= values_[i + 3]) e.nearest = std::min(e.nearest, values_[i]), e.furthest = std::max(e.furthest, values_[i + 3]);
        return e.nearest > e.furthest ? depth_extent{} : e;
    }

private:
    program program_;
    texture map_;
    int resolution_ = 0;
    std::vector<float> values_;
};

/// Sets the light's frustum uniforms of lookup/light.glsl (hs_lookup_*) on `prog`.
inline void set_lookup_frustum(GLuint prog, const light_space& light) {
    glUniformMatrix4fv(glGetUniformLocation(prog, "hs_lookup_view_projection"), 1, GL_FALSE, &light.view_projection()[0][0]);
    glUniformMatrix4fv(glGetUniformLocation(prog, "hs_lookup_view"), 1, GL_FALSE, &light.view()[0][0]);
    glUniform1f(glGetUniformLocation(prog, "hs_lookup_near"), light.near_plane());
    glUniform1f(glGetUniformLocation(prog, "hs_lookup_far"), light.far_plane());
    glUniform1i(glGetUniformLocation(prog, "hs_lookup_resolution"), light.resolution());
}

/// Sets the uniforms of a look-up (hs_lookup_*) for `light`'s map, and binds the range map to `unit`.
inline void set_lookup_uniforms(GLuint prog, const light_space& light, const depth_range_pass& range, int unit) {
    set_lookup_frustum(prog, light);
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, range.map().get());
    glUniform1i(glGetUniformLocation(prog, "hs_range_texture"), unit);
    glActiveTexture(GL_TEXTURE0);
}

} // namespace hairshadow::gl
