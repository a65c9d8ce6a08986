#pragma once
/// @file
/// Approximate deep shadow maps on GL (AMD TressFX): the light pass's depth map is all the fixed
/// density needs, so its build draws nothing more; the measured density adds one additive pass that
/// sums each texel's optical depth and fragment count into an RG32F texture. The look-up composes
/// lookup/light with reconstruction/fibre_density, whose uniforms carry the fibre parameters.

#include <hairshadow/gl/maps/interpolated_maps.hpp>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// GL twin of a shadow_method whose reconstruction is fibre_density.
template <class Method>
class fibre_density_maps_gl : public detail::maps_base<typename Method::placement_type> {
    using P = typename Method::placement_type;
    using R = typename Method::reconstruction_type;
    using base = detail::maps_base<P>;
    static constexpr bool measured = R::template stored_maps<P> > 0;
    static_assert(!measured || std::is_same_v<typename Method::accumulation_type, float_accumulation>,
                  "the measured fibre density sums in float on GL");

public:
    /// Texture units the look-up reads (bind_lookup binds them from its first_unit): the range map, and
    /// the measured density's sums.
    static constexpr int texture_units = measured ? 2 : 1;

    /// Takes the CPU method's policies (the fibre parameters); throws feature_error without GL 4.3.
    explicit fibre_density_maps_gl(const Method& method = Method()) : base(method.placement()), reconstruction_(method.reconstruction()) {
        require_version(4, 3, "approximate deep shadow maps on GL");
        if constexpr (measured) count_program_ = detail::link_line_pass(shaders::passes_fibre_count, "fibre count pass");
    }

    /// GLSL defining float hs_transmittance(vec3 world_pos), with every name under `prefix`: prepend a
    /// version line; bind with bind_lookup(program, first_unit, prefix).
    static std::string lookup_source(std::string_view prefix = default_lookup_prefix) {
        std::string s = measured ? "#define HS_MEASURED_DENSITY\n" : "";
        for (auto piece : {shaders::arithmetic_exact_division, shaders::placement_common, shaders::lookup_light, shaders::reconstruction_fibre_density}) s += piece;
        return prefix_glsl(std::string(lookup_version_check) + s, prefix);
    }

    /// Builds the maps of `mesh` seen from `light`, with a light pass of their own.
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) { build(this->own_pass(mesh, light, options)); }

    /// Builds the maps from a light pass that has run (shared with other methods for the same light).
    void build(const light_pass& pass) {
        this->adopt_pass(pass);
        reconstruction_.prepare(this->light_);
        if constexpr (measured) {
            state_guard guard("hairshadow: fibre density");
            guard.set_pass_state();
            const int res = this->light_.resolution();
            if (res != allocated_) {
                sums_ = make_texture_2d(GL_RG32F, res, res);
                allocated_ = res;
            }
            if (pass.compute()) {
                // shaders/compute/fibre_count: one work group per tile of the light pass's lists.
                const GLuint prog = compute_program_.for_run(*pass.compute(), [](const std::string& alpha) {
                    return detail::link_compute_pass(alpha + "#define HS_SUM_SLOTS 1\n", {shaders::accumulation_float, shaders::compute_tile_sums},
                                                     shaders::compute_fibre_count, "compute/fibre_count");
                });
                glUseProgram(prog);
                pass.compute()->bind_for_tiles(prog);
                glBindImageTexture(0, sums_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
                pass.compute()->dispatch_tiles();
                glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            } else {
                glBindFramebuffer(GL_FRAMEBUFFER, this->fbo_.get());
                glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, sums_.get(), 0);
                for (int t = 1; t < 8; ++t) glFramebufferTexture(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), 0, 0);
                const GLenum attachment = GL_COLOR_ATTACHMENT0;
                glDrawBuffers(1, &attachment);
                if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("fibre density: incomplete framebuffer");
                glViewport(0, 0, res, res);
                const float zero[4] = {0, 0, 0, 0};
                glClearBufferfv(GL_COLOR, 0, zero);
                glEnable(GL_BLEND);
                glBlendEquation(GL_FUNC_ADD);
                glBlendFunc(GL_ONE, GL_ONE);
                glUseProgram(count_program_.get());
                set_light_uniforms(count_program_.get(), this->light_, pass.options());
                pass.mesh().draw();
            }
            check("fibre density: count pass");
        }
        this->built();
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename Method::texel_maps> read_back() {
        const auto range = detail::read_range(this->checked_range());
        const P& placement = this->placement_from(range);
        const int res = this->light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<float> sums(measured ? 2 * n : 0);
        if constexpr (measured) {
            state_guard guard("hairshadow: fibre density read-back");
            guard.set_pass_state();
            glBindTexture(GL_TEXTURE_2D, sums_.get());
            glGetTexImage(GL_TEXTURE_2D, 0, GL_RG, GL_FLOAT, sums.data());
            check("fibre density read-back");
        }
        std::vector<typename Method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            const float* texel_range = &range[4 * i];
            if (texel_range[0] > texel_range[3]) continue; // no fragment: the CPU leaves the texel zero
            out[i].placement = detail::range_state{}.texel_state(placement, texel_range, i);
            if constexpr (measured) {
                out[i].data.optical_depth = sums[2 * i];
                out[i].data.fragments = std::uint32_t(sums[2 * i + 1]);
            } else {
                out[i].data.any = true;
            }
        }
        return out;
    }

    /// The maps read back as the CPU method, for CPU queries of maps built on GL.
    Method to_cpu() {
        auto texels = read_back();
        Method cpu(this->placement(), reconstruction_);
        cpu.adopt(this->light_, this->placement(), std::move(texels));
        return cpu;
    }

    /// Sets the look-up's uniforms on `prog` (which need not be current) and binds its textures to
    /// units [first_unit, first_unit + texture_units), with no sampler objects; `prefix` is the one
    /// given to lookup_source, `depth_bias` the linear depth each point moves towards the light (as
    /// query_options::depth_bias). The active texture unit and the current program are left as found.
    /// Throws argument_error where `prog` is not a linked program or lacks one of the look-up's uniforms.
    void bind_lookup(GLuint prog, int first_unit = 0, std::string_view prefix = default_lookup_prefix, float depth_bias = 0.0f) const {
        lookup_binder binder(prog, first_unit, prefix, depth_bias);
        this->bind_light(binder);
        if constexpr (measured) {
            binder.texture("hs_density_texture", GL_TEXTURE_2D, sums_.get()); // the fixed density's uniforms go unread
        } else {
            const auto& fibres = reconstruction_.parameters();
            binder.set("hs_fibre_step", fibres.fibre_step());
            binder.set("hs_fibre_optical_depth", fibres.fibre_optical_depth());
            // No cap is infinity on the CPU; GLSL need not keep an infinite uniform, and the largest
            // float caps nothing a finite count reaches.
            binder.set("hs_max_fibres", std::min(fibres.max_fibres, std::numeric_limits<float>::max()));
        }
    }

    /// New fibre parameters for the look-up, without a rebuild: they are only uniforms (bind again).
    void set_parameters(const fibre_density_parameters& parameters) {
        R changed(parameters); // checks them
        changed.prepare(this->light_);
        reconstruction_ = changed;
    }
    const fibre_density_parameters& parameters() const noexcept { return reconstruction_.parameters(); }

    /// Bytes of the textures the look-up reads: the depth range (RGBA32F, one extra row) and the
    /// measured density's sums (RG32F), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t res = this->range_ ? std::size_t(this->range_->resolution) : 0;
        return 16 * res * (res + 1) + (measured ? 8 * res * res : 0);
    }

private:
    R reconstruction_;
    int allocated_ = 0;
    program count_program_;
    detail::compute_pass_program compute_program_;
    texture sums_;
};

} // namespace hairshadow::gl
