#pragma once
/// @file
/// The projected methods on GL (Fourier opacity maps, moment shadow maps: a reconstruction built on
/// detail::depth_projection): after the light pass's depth-range map, one pass adds every fragment's
/// N terms at its place in its texel's range into the layers of an RGBA32F 2D array texture, four
/// sums a layer (RGBA8 with an 8-bit accumulation, which adds the encoded terms, each quantised:
/// reconstruction/detail/depth_projection.hpp). The raster path blends them additively (up to 8
/// targets, 32 sums, in one draw); the compute path sums them in fixed point (or as integer 8-bit
/// steps), in any order to the same bits. Both the passes and the
/// look-up are composed from the reconstruction's GLSL (hs_projection_terms, hs_total_optical_depth,
/// hs_series_optical_depth, with its defines and uniforms), so a new projection brings only that.

#include <hairshadow/gl/maps/interpolated_maps.hpp>
#include <hairshadow/reconstruction/detail/depth_projection.hpp>

#include <array>
#include <algorithm>
#include <string>
#include <type_traits>
#include <vector>

namespace hairshadow::gl {

/// GL twin of a shadow_method whose reconstruction projects depths on N functions.
template <class Method>
class projected_maps_gl : public detail::maps_base<typename Method::placement_type> {
    using P = typename Method::placement_type;
    using R = typename Method::reconstruction_type;
    using A = typename Method::accumulation_type;
    using accumulation = accumulation_glsl<A>;
    using base = detail::maps_base<P>;
    static_assert(std::is_base_of_v<hairshadow::detail::depth_projection<R, R::sums>, R>, "projected_maps_gl needs a reconstruction built on depth_projection");
    static_assert(R::sums <= 32, "one raster pass writes at most 8 targets of 4 sums");

public:
    static constexpr int sums = R::sums;
    static constexpr int array_layers = (sums + 3) / 4;
    /// Texture units the look-up reads (bind_lookup binds them from its first_unit): the range map and the sums.
    static constexpr int texture_units = 2;

    /// Compiles the raster pass; throws feature_error without GL 4.3 or with too few draw buffers.
    explicit projected_maps_gl(const Method& method = Method()) : base(method.placement()), reconstruction_(method.reconstruction()) {
        require_version(4, 3, "projected shadow maps on GL");
        GLint draw_buffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
        if (draw_buffers < array_layers) throw feature_error("this projected method needs " + std::to_string(array_layers) + " draw buffers");
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
        const auto fs = compile_stage(GL_FRAGMENT_SHADER, defines(),
                                      {shaders::raster_coverage, accumulation::source(), shaders::arithmetic_exact_division, shaders::placement_common, reconstruction_source(),
                                       shaders::reconstruction_depth_projection, shaders::passes_projection},
                                      "passes/projection");
        raster_program_ = link_program({&vs, &fs}, "projection pass");
    }

    /// GLSL defining float hs_transmittance(vec3 world_pos), with every name under `prefix`: prepend a
    /// version line; bind with bind_lookup(program, first_unit, prefix).
    static std::string lookup_source(std::string_view prefix = default_lookup_prefix) {
        std::string s = defines();
        for (auto piece : {accumulation::source(), shaders::arithmetic_exact_division, shaders::placement_common, reconstruction_source(), shaders::reconstruction_depth_projection,
                           shaders::lookup_light, shaders::lookup_projection})
            s += piece;
        return prefix_glsl(std::string(lookup_version_check) + s, prefix);
    }

    /// Builds the maps of `mesh` seen from `light`, with a light pass of their own.
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) { build(this->own_pass(mesh, light, options)); }

    /// Builds the maps from a light pass that has run (shared with other methods for the same light).
    void build(const light_pass& pass) {
        this->adopt_pass(pass);
        state_guard guard("hairshadow: projected maps");
        guard.set_pass_state();
        const int res = this->light_.resolution();
        allocate(res);
        if (pass.compute()) {
            // shaders/compute/projection: one work group per tile of the light pass's lists, as many sums
            // a walk as shared memory holds beside the texels' ranges (8 bytes a sum, 4 for 8-bit steps).
            const GLuint prog = compute_program_.for_run(*pass.compute(), [this](const std::string& alpha) {
                return detail::link_compute_pass(alpha + compute_defines() + "#define HS_SUM_SLOTS " +
                                                     std::to_string(detail::sums_per_walk(sums, accumulation::unorm8 ? 4 : 8, detail::compute_tile * detail::compute_tile * 8)) +
                                                     "\n",
                                                 {accumulation::source(), shaders::compute_tile_sums, shaders::arithmetic_exact_division, shaders::placement_common,
                                                  reconstruction_source(), shaders::reconstruction_depth_projection},
                                                 shaders::compute_projection, "compute/projection");
            });
            this->begin_compute_pass(pass, prog);
            detail::set_policy_uniforms(lookup_binder::for_pass(prog, 1), reconstruction_);
            glBindImageTexture(0, sums_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, accumulation::texture_format);
            pass.compute()->dispatch_tiles();
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            check("projected maps: compute pass");
            this->built();
            return;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, this->fbo_.get());
        std::array<GLenum, 8> buffers{}; // no allocation in a frame
        GLsizei used_buffers = 0;
        for (int t = 0; t < 8; ++t) {
            if (t < array_layers) {
                glFramebufferTextureLayer(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), sums_.get(), 0, t);
                buffers[std::size_t(used_buffers++)] = GLenum(GL_COLOR_ATTACHMENT0 + t);
            } else {
                glFramebufferTexture(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), 0, 0);
            }
        }
        glDrawBuffers(used_buffers, buffers.data());
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("projected maps: incomplete framebuffer");
        glViewport(0, 0, res, res);
        const float zero[4] = {0, 0, 0, 0};
        for (GLsizei t = 0; t < used_buffers; ++t) glClearBufferfv(GL_COLOR, t, zero);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(raster_program_.get());
        set_light_uniforms(raster_program_.get(), this->light_, pass.options());
        auto binder = lookup_binder::for_pass(raster_program_.get(), 0);
        binder.texture("hs_range_map", GL_TEXTURE_2D, this->range_->range.get());
        detail::set_policy_uniforms(binder, reconstruction_);
        pass.mesh().draw();
        check("projected maps: raster pass");
        this->built();
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename Method::texel_maps> read_back() {
        const auto range = detail::read_range(this->checked_range());
        const P& placement = this->placement_from(range);
        const int res = this->light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<typename A::value_type> stored(4 * n * std::size_t(array_layers));
        {
            state_guard guard("hairshadow: projected maps read-back");
            guard.set_pass_state();
            glBindTexture(GL_TEXTURE_2D_ARRAY, sums_.get());
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA, accumulation::pixel_type, stored.data());
            check("projected maps read-back");
        }
        std::vector<typename Method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            const float* texel_range = &range[4 * i];
            if (texel_range[0] > texel_range[3]) continue; // no fragment: the CPU leaves the texel zero
            out[i].placement = detail::range_state{}.texel_state(placement, texel_range, i);
            for (int k = 0; k < sums; ++k) out[i].data.sums[std::size_t(k)] = stored[4 * n * std::size_t(k / 4) + 4 * i + std::size_t(k % 4)];
        }
        return out;
    }

    /// The maps read back as the CPU method (with the reconstruction's parameters), for CPU queries.
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
        binder.texture("hs_sums_texture", GL_TEXTURE_2D_ARRAY, sums_.get());
        detail::set_policy_uniforms(binder, reconstruction_);
    }

    /// Bytes of the textures the look-up reads: the depth range (RGBA32F, one extra row) and the sums
    /// (RGBA32F or RGBA8 layers), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t res = std::size_t(allocated_);
        return 16 * res * (res + 1) + accumulation::texel_bytes * res * res * std::size_t(array_layers);
    }

private:
    /// The reconstruction's defines, and HS_EIGHT_BIT where the accumulation stores 8-bit steps.
    static std::string defines() {
        return common_defines() + (accumulation::unorm8 ? "#define HS_EIGHT_BIT\n" : "");
    }
    static std::string compute_defines() { return common_defines() + accumulation::image_defines("HS_SUMS_FORMAT"); }
    static std::string common_defines() {
        return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n" + accumulation::defines() + detail::policy_defines<R>() +
               "#define HS_TERMS_PER_OPTICAL_DEPTH " + std::to_string(int(hairshadow::detail::terms_per_optical_depth<R>())) + ".0\n";
    }
    static std::string_view reconstruction_source() { return detail::policy_source<R>(R::glsl_name); }
    void allocate(int res) {
        if (res == allocated_) return;
        sums_ = make_texture();
        glBindTexture(GL_TEXTURE_2D_ARRAY, sums_.get());
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, accumulation::texture_format, res, res, array_layers);
        allocated_ = res;
    }

    R reconstruction_;
    int allocated_ = 0;
    program raster_program_;
    detail::compute_pass_program compute_program_;
    texture sums_;
};

} // namespace hairshadow::gl
