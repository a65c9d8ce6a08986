#pragma once
/// @file
/// Density clustering's per-texel state on GL (Mertens et al. 2004, section 3.3): after the light
/// pass, one additive pass for the k-means iteration (weights and weighted depths), one for the
/// clusters' variances, and a full-screen pass resolving them into the means and standard deviations
/// that the histogram pass and the look-up read (a 2D array texture: means, then sigmas).

#include <hairshadow/gl/passes/light_pass.hpp>
#include <hairshadow/gl/lookup/lookup_binding.hpp>
#include <hairshadow/gl/maps/policy_glsl.hpp>
#include <hairshadow/placement/clustered.hpp>

#include <array>
#include <algorithm>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// The cluster means and standard deviations of clustered<K> maps.
template <int K>
class cluster_state_pass {
public:
    /// RGBA layers per quantity (four clusters each).
    static constexpr int targets = (K + 3) / 4;

    /// Compiles the passes; throws feature_error if the context has fewer than 2 x targets draw buffers.
    cluster_state_pass() {
        GLint draw_buffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
        if (draw_buffers < 2 * targets)
            throw feature_error("density clustering with " + std::to_string(K) + " clusters needs " + std::to_string(2 * targets) +
                                " draw buffers (GL_MAX_DRAW_BUFFERS is " + std::to_string(draw_buffers) + ")");
        const std::string defines = "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n#define HS_LAYERS " +
                                    std::to_string(K) + "\n#define HS_STATE_TARGETS " + std::to_string(targets) + "\n";
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
        const auto fullscreen = compile_stage(GL_VERTEX_SHADER, {}, {shaders::passes_fullscreen_vertex}, "passes/fullscreen_vertex");
        // The fragment passes read the rasterised fragment (raster/coverage); the resolve pass does not.
        const auto compile = [&](std::string_view pass, std::string_view source, bool fragments) {
            return compile_stage(GL_FRAGMENT_SHADER, {},
                                  {defines, fragments ? shaders::raster_coverage : "", shaders::arithmetic_exact_division, shaders::placement_common,
                                   shaders::placement_clustered, shaders::passes_cluster_common, source},
                                  std::string(pass));
        };
        const auto means = compile("passes/cluster_means", shaders::passes_cluster_means, true);
        const auto variance = compile("passes/cluster_variance", shaders::passes_cluster_variance, true);
        const auto resolve = compile("passes/cluster_resolve", shaders::passes_cluster_resolve, false);
        means_program_ = link_program({&vs, &means}, "cluster means pass");
        variance_program_ = link_program({&vs, &variance}, "cluster variance pass");
        resolve_program_ = link_program({&fullscreen, &resolve}, "cluster resolve pass");
    }

    /// GLSL defines the clustered snippets need.
    static std::string defines() { return "#define HS_STATE_TARGETS " + std::to_string(targets) + "\n"; }

    /// Computes the state of every texel of `mesh` seen from `light`, after the light pass that made
    /// `range`, drawing through framebuffer `fbo`; within a build's state_guard.
    void run(const hair_mesh& mesh, const light_space& light, const raster_options& options, const detail::range_textures& range, GLuint fbo) {
        const int res = light.resolution();
        allocate(res);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, res, res);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, range.range.get());
        // 1. k-means iteration, 2. variances: additive passes over the fragments.
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        for (const auto* pass : {&means_program_, &variance_program_}) {
            const bool second = pass == &variance_program_;
            attach(second ? variance_ : sums_, true);
            glUseProgram(pass->get());
            set_light_uniforms(pass->get(), light, options);
            glUniform1i(glGetUniformLocation(pass->get(), "hs_range_map"), 0);
            glActiveTexture(GL_TEXTURE1);
            glBindTexture(GL_TEXTURE_2D_ARRAY, second ? sums_.get() : 0); // pass 1 writes the sums
            glUniform1i(glGetUniformLocation(pass->get(), "hs_cluster_sums"), 1);
            glActiveTexture(GL_TEXTURE0);
            mesh.draw();
        }
        glDisable(GL_BLEND);
        // 3. Means and standard deviations, texel by texel.
        attach(state_, false);
        glUseProgram(resolve_program_.get());
        glUniform1i(glGetUniformLocation(resolve_program_.get(), "hs_range_map"), 0);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D_ARRAY, sums_.get());
        glUniform1i(glGetUniformLocation(resolve_program_.get(), "hs_cluster_sums"), 1);
        glActiveTexture(GL_TEXTURE2);
        glBindTexture(GL_TEXTURE_2D_ARRAY, variance_.get());
        glUniform1i(glGetUniformLocation(resolve_program_.get(), "hs_cluster_variance"), 2);
        glActiveTexture(GL_TEXTURE0);
        glBindVertexArray(empty_vao_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        check("cluster state passes");
    }

    /// Texture units bind() takes.
    static constexpr int texture_units = 1;
    /// Binds the state for a histogram pass or a look-up (sampler hs_cluster_state) on the binder's next unit.
    void bind(lookup_binder& b) const { b.texture("hs_cluster_state", GL_TEXTURE_2D_ARRAY, state_.get()); }

    /// Reads the state back for texel_state(); for tests and inspection.
    void read_back() {
        values_.resize(std::size_t(4 * 2 * targets) * std::size_t(resolution_) * std::size_t(resolution_));
        glBindTexture(GL_TEXTURE_2D_ARRAY, state_.get());
        glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA, GL_FLOAT, values_.data());
        check("cluster state read-back");
    }
    /// Texel i's means and standard deviations, after read_back().
    typename clustered<K>::texel_state texel_state(const clustered<K>&, const float*, std::size_t i) const {
        const std::size_t n = std::size_t(resolution_) * std::size_t(resolution_);
        typename clustered<K>::texel_state s;
        for (std::size_t j = 0; j < std::size_t(K); ++j) {
            s.mean[j] = values_[4 * n * (j / 4) + 4 * i + j % 4];
            s.sigma[j] = values_[4 * n * (std::size_t(targets) + j / 4) + 4 * i + j % 4];
        }
        return s;
    }

    /// The state texture (means, then deviations; RGBA32F layers) at resolution `res`, for the compute
    /// build to write.
    GLuint state_texture(int res) {
        allocate(res);
        return state_.get();
    }

private:

    void allocate(int res) {
        if (res == resolution_) return;
        for (auto* t : {&sums_, &variance_, &state_}) {
            *t = make_texture();
            glBindTexture(GL_TEXTURE_2D_ARRAY, t->get());
            glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32F, res, res, 2 * targets);
        }
        resolution_ = res;
    }
    /// Attaches the 2 x targets layers of `t` as the colour targets, cleared to zero if asked.
    static void attach(const texture& t, bool clear) {
        std::array<GLenum, 2 * targets> buffers{}; // no allocation in a frame
        for (int i = 0; i < 2 * targets; ++i) {
            glFramebufferTextureLayer(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), t.get(), 0, i);
            buffers[std::size_t(i)] = GLenum(GL_COLOR_ATTACHMENT0 + i);
        }
        glDrawBuffers(GLsizei(buffers.size()), buffers.data());
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("cluster state: incomplete framebuffer");
        const float zero[4] = {0, 0, 0, 0};
        if (clear)
            for (int i = 0; i < 2 * targets; ++i) glClearBufferfv(GL_COLOR, i, zero);
    }

    program means_program_, variance_program_, resolve_program_;
    texture sums_, variance_, state_;
    vertex_array empty_vao_ = make_vertex_array();
    int resolution_ = 0;
    std::vector<float> values_;
};

/// Density clustering's texels take their state from these passes (gl/maps/policy_glsl.hpp).
template <int K>
struct state_pass_of<clustered<K>> {
    using type = cluster_state_pass<K>;
};

} // namespace hairshadow::gl
