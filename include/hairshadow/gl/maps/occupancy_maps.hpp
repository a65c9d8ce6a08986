#pragma once
/// @file
/// Occupancy maps on GL (Sintorn & Assarsson 2009, section 3.1): the light pass (light_pass.hpp: MIN /
/// MAX blending), an occupancy pass (RGBA32UI targets, glLogicOp(GL_OR)) and a slab pass (additive RGBA32F,
/// or RGBA8 for emulated 8 bits), the programs composed from the same policy snippets as the CPU
/// kernels' GLSL twins; and the GLSL look-up hs_transmittance(vec3) for user shaders. Any contiguous
/// placement works (the published depth range, or the per-pixel-depth hybrid).

#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/maps/interpolated_maps.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/methods/published.hpp>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// GL twin of a shadow_method whose reconstruction is occupancy_bitcount<B>.
template <class Method>
class occupancy_maps_gl : public detail::maps_base<typename Method::placement_type> {
    using P = typename Method::placement_type;
    using A = typename Method::accumulation_type;
    using base = detail::maps_base<P>;
    static constexpr int S = P::layer_count;
    static constexpr int B = Method::reconstruction_type::slab_count;
    using accumulation = accumulation_glsl<A>;

public:
    static constexpr int bit_targets = (S + 127) / 128;
    static constexpr int slab_targets = (B + 3) / 4;
    /// Whether build_path::compute builds these maps (else the raster passes run after a compute light
    /// pass): its images fit 4 units, and a tile's bits and sums 30 KiB of shared memory.
    static constexpr bool computes_on_gpu = range_placement<P> && bit_targets + slab_targets <= 4 && S * 32 + B * 2048 + 2048 <= 30 * 1024;
    /// Texture units the look-up reads (bind_lookup binds them from its first_unit): the range map,
    /// the occupancy words and the slabs.
    static constexpr int texture_units = 1 + bit_targets + slab_targets;
    using cpu_method = Method;

    /// Compiles the passes; throws feature_error if the context lacks GL 4.3 or enough draw buffers.
    explicit occupancy_maps_gl(P placement = P()) : base(std::move(placement)) {
        require_version(4, 3, "occupancy maps on GL");
        GLint draw_buffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
        if (draw_buffers < std::max(bit_targets, slab_targets))
            throw feature_error("occupancy maps with " + std::to_string(S) + " slices and " + std::to_string(B) + " slabs need " +
                                std::to_string(std::max(bit_targets, slab_targets)) + " draw buffers; the context has " +
                                std::to_string(draw_buffers));
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
        const std::string defs = defines();
        auto fragment = [&](std::string_view pass, const char* name) {
            return compile_stage(GL_FRAGMENT_SHADER, defs,
                                 around_placement<P>({shaders::raster_coverage, accumulation::source(), shaders::arithmetic_exact_division, shaders::placement_common}, {pass}), name);
        };
        const auto bits_fs = fragment(shaders::passes_occupancy_bits, "passes/occupancy_bits");
        const auto slabs_fs = fragment(shaders::passes_occupancy_slabs, "passes/occupancy_slabs");
        bits_program_ = link_program({&vs, &bits_fs}, "occupancy pass");
        slabs_program_ = link_program({&vs, &slabs_fs}, "slab pass");
    }

    /// GLSL defining float hs_transmittance(vec3 world_pos), with every name under `prefix` (so
    /// "key_" defines key_transmittance): prepend a version line; bind with bind_lookup(program,
    /// first_unit, prefix). Any number of look-ups with different prefixes share one shader.
    static std::string lookup_source(std::string_view prefix = default_lookup_prefix) {
        std::string s = defines();
        for (auto piece : around_placement<P>({accumulation::source(), shaders::arithmetic_exact_division, shaders::placement_common},
                                              {shaders::reconstruction_occupancy_bitcount, shaders::lookup_light, shaders::lookup_occupancy_texels,
                                               shaders::lookup_occupancy}))
            s += piece;
        return prefix_glsl(std::string(lookup_version_check) + s, prefix);
    }

    /// Builds the maps of `mesh` seen from `light`, with a light pass of their own.
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) { build(this->own_pass(mesh, light, options)); }

    /// Builds the maps from a light pass that has run (shared with other methods for the same light):
    /// its mesh, light and options. The maps read its range map: run it again, and build them again.
    void build(const light_pass& pass) {
        this->adopt_pass(pass);
        state_guard guard("hairshadow: occupancy maps");
        guard.set_pass_state();
        allocate(this->light_.resolution());
        if (pass.compute() && computes_on_gpu) {
            build_compute(pass);
            check("occupancy maps: compute pass");
            this->built();
            return;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, this->fbo_.get());
        glViewport(0, 0, allocated_, allocated_);

        // 1. Occupancy bits: OR of each fragment's slice bit.
        attach(bits_);
        const GLuint zero_u[4] = {0, 0, 0, 0};
        for (int i = 0; i < bit_targets; ++i) glClearBufferuiv(GL_COLOR, i, zero_u);
        glEnable(GL_COLOR_LOGIC_OP);
        glLogicOp(GL_OR);
        draw(bits_program_, pass);
        glDisable(GL_COLOR_LOGIC_OP);
        check("occupancy maps: occupancy pass");

        // 2. Slabs: additive sums of optical depth.
        attach(slabs_);
        const float zero_f[4] = {0, 0, 0, 0};
        for (int i = 0; i < slab_targets; ++i) glClearBufferfv(GL_COLOR, i, zero_f);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        draw(slabs_program_, pass);
        check("occupancy maps: slab pass");
        this->built();
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename cpu_method::texel_maps> read_back() {
        const auto range = detail::read_range(this->checked_range());
        const P& placement = this->placement_from(range);
        const int res = this->light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<typename A::value_type> slabs(4 * n * std::size_t(slab_targets));
        std::vector<std::uint32_t> bits(4 * n * std::size_t(bit_targets));
        {
            state_guard guard("hairshadow: occupancy maps read-back");
            guard.set_pass_state();
            for (int t = 0; t < bit_targets; ++t) {
                glBindTexture(GL_TEXTURE_2D, bits_[std::size_t(t)].get());
                glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, bits.data() + 4 * n * std::size_t(t));
            }
            for (int t = 0; t < slab_targets; ++t) {
                glBindTexture(GL_TEXTURE_2D, slabs_[std::size_t(t)].get());
                glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, accumulation::pixel_type, slabs.data() + 4 * n * std::size_t(t));
            }
            check("occupancy maps read-back");
        }
        std::vector<typename cpu_method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            auto& t = out[i];
            const float* texel_range = &range[4 * i];
            if (texel_range[0] > texel_range[3]) continue; // no fragment: the CPU leaves the texel zero
            t.placement = detail::range_state{}.texel_state(placement, texel_range, i);
            for (int w = 0; w < S / 32; ++w) t.data.bits[std::size_t(w)] = bits[4 * n * std::size_t(w / 4) + 4 * i + std::size_t(w % 4)];
            for (int s = 0; s < B; ++s) t.data.slabs[std::size_t(s)] = slabs[4 * n * std::size_t(s / 4) + 4 * i + std::size_t(s % 4)];
        }
        return out;
    }

    /// Sets the look-up's uniforms on `prog` (which need not be current) and binds its textures to
    /// units [first_unit, first_unit + texture_units), with no sampler objects; `prefix` is the one
    /// given to lookup_source, `depth_bias` the linear depth each point moves towards the light (as
    /// query_options::depth_bias). The active texture unit and the current program are left as found.
    /// Throws argument_error where `prog` is not a linked program or lacks one of the look-up's uniforms.
    void bind_lookup(GLuint prog, int first_unit = 0, std::string_view prefix = default_lookup_prefix, float depth_bias = 0.0f) const {
        lookup_binder binder(prog, first_unit, prefix, depth_bias);
        this->bind_light(binder);
        for (int t = 0; t < bit_targets; ++t) binder.texture("hs_bits_texture", GL_TEXTURE_2D, bits_[std::size_t(t)].get(), t);
        for (int t = 0; t < slab_targets; ++t) binder.texture("hs_slabs_texture", GL_TEXTURE_2D, slabs_[std::size_t(t)].get(), t);
    }

    /// Bytes of the textures the look-up reads: depth range (RGBA32F, one extra row), occupancy bits
    /// (RGBA32UI) and slabs (RGBA32F or RGBA8), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t texels = std::size_t(allocated_) * std::size_t(allocated_);
        return 16 * std::size_t(allocated_) * std::size_t(allocated_ + 1) + texels * (16 * std::size_t(bit_targets) + accumulation::texel_bytes * std::size_t(slab_targets));
    }

    /// The maps read back as the CPU method, for CPU queries of maps built on GL.
    Method to_cpu() {
        auto texels = read_back();
        Method cpu;
        cpu.adopt(this->light_, this->placement(), std::move(texels));
        return cpu;
    }

private:
    static std::string defines() {
        return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n#define HS_LAYERS " + std::to_string(S) +
               "\n#define HS_SLABS " + std::to_string(B) + "\n#define HS_BIT_TARGETS " + std::to_string(bit_targets) +
               "\n#define HS_SLAB_TARGETS " + std::to_string(slab_targets) + "\n" + accumulation::defines() + placement_glsl<P>::defines();
    }

    void allocate(int res) {
        if (res == allocated_) return;
        auto make = [&](GLenum format) { return make_texture_2d(format, res, res); };
        bits_.clear();
        slabs_.clear();
        for (int t = 0; t < bit_targets; ++t) bits_.push_back(make(GL_RGBA32UI));
        for (int t = 0; t < slab_targets; ++t) slabs_.push_back(make(accumulation::texture_format));
        allocated_ = res;
    }

    /// The compute build (shaders/compute/occupancy): one work group per tile of the light pass's lists.
    void build_compute(const light_pass& pass) {
        const GLuint prog = compute_program_.for_run(*pass.compute(), [](const std::string& alpha) {
            const std::string d = alpha + defines() + "#define HS_SUM_SLOTS " + std::to_string(B) + "\n" + accumulation::image_defines("HS_SLABS_FORMAT");
            return detail::link_compute_pass(d, around_placement<P>({accumulation::source(), shaders::compute_tile_sums, shaders::arithmetic_exact_division, shaders::placement_common}, {}),
                                             shaders::compute_occupancy, "compute/occupancy");
        });
        this->begin_compute_pass(pass, prog);
        for (int t = 0; t < bit_targets; ++t)
            glBindImageTexture(GLuint(t), bits_[std::size_t(t)].get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32UI);
        for (int t = 0; t < slab_targets; ++t)
            glBindImageTexture(GLuint(bit_targets + t), slabs_[std::size_t(t)].get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, accumulation::texture_format);
        pass.compute()->dispatch_tiles();
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    }

    static void attach(const std::vector<texture>& textures) {
        std::array<GLenum, 8> buffers{}; // no allocation in a frame; the constructor checked the count
        for (std::size_t i = 0; i < 8; ++i) glFramebufferTexture(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), i < textures.size() ? textures[i].get() : 0, 0);
        for (std::size_t i = 0; i < textures.size() && i < buffers.size(); ++i) buffers[i] = GLenum(GL_COLOR_ATTACHMENT0 + i);
        glDrawBuffers(GLsizei(std::min<std::size_t>(textures.size(), buffers.size())), buffers.data());
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("occupancy maps: incomplete framebuffer");
    }

    void draw(const program& p, const light_pass& pass) const {
        glUseProgram(p.get());
        set_light_uniforms(p.get(), this->light_, pass.options());
        auto binder = lookup_binder::for_pass(p.get(), 0);
        binder.texture("hs_range_map", GL_TEXTURE_2D, this->range_->range.get());
        placement_glsl<P>::set_uniforms(binder, this->placement_spec());
        pass.mesh().draw();
    }

    int allocated_ = 0;
    program bits_program_, slabs_program_;
    detail::compute_pass_program compute_program_;
    std::vector<texture> bits_, slabs_;
};

} // namespace hairshadow::gl
