#pragma once
/// @file
/// Occupancy maps on GL (Sintorn & Assarsson 2009, section 3.1): a depth-range pass (MIN / MAX
/// blending), an occupancy pass (RGBA32UI targets, glLogicOp(GL_OR)) and a slab pass (additive RGBA32F,
/// or RGBA8 for emulated 8 bits), the programs composed from the same policy snippets as the CPU
/// kernels' GLSL twins; and the GLSL look-up hs_transmittance(vec3) for user shaders. Any contiguous
/// placement works (the published depth range, or the per-pixel-depth hybrid).

#include <hairshadow/gl/context.hpp>
#include <hairshadow/gl/depth_range_pass.hpp>
#include <hairshadow/gl/hair_mesh.hpp>
#include <hairshadow/gl/interpolated_maps.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/methods/published.hpp>

#include <string>
#include <vector>

namespace hairshadow::gl {

/// GL twin of a shadow_method whose reconstruction is occupancy_bitcount<B>.
template <class Method>
class occupancy_maps_gl {
    using P = typename Method::placement_type;
    using A = typename Method::accumulation_type;
    static constexpr int S = P::layer_count;
    static constexpr int B = Method::reconstruction_type::slab_count;
    static constexpr bool eight_bit = std::is_same_v<A, emulated_8bit>;

public:
    static constexpr int bit_targets = (S + 127) / 128;
    static constexpr int slab_targets = (B + 3) / 4;
    using cpu_method = Method;

    /// Compiles the passes; throws feature_error if the context lacks GL 4.3 or enough draw buffers.
    explicit occupancy_maps_gl(P placement = P()) : placement_(std::move(placement)) {
        require_version(4, 3, "occupancy maps on GL");
        GLint draw_buffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
        if (draw_buffers < std::max(bit_targets, slab_targets))
            throw feature_error("occupancy maps with " + std::to_string(S) + " slices and " + std::to_string(B) + " slabs need " +
                                std::to_string(std::max(bit_targets, slab_targets)) + " draw buffers; the context has " +
                                std::to_string(draw_buffers));
        const auto vs = compile_shader(GL_VERTEX_SHADER, {version, shaders::raster_vertex}, "raster/vertex");
        const std::string defs = defines();
        auto fragment = [&](std::string_view pass, const char* name) {
            return compile_shader(GL_FRAGMENT_SHADER, {version, defs, shaders::raster_coverage, accumulation_snippet(), shaders::placement_common,
                                                       detail::placement_glsl<P>::snippet, detail::placement_glsl<P>::state, pass},
                                  name);
        };
        const auto bits_fs = fragment(shaders::passes_occupancy_bits, "passes/occupancy_bits");
        const auto slabs_fs = fragment(shaders::passes_occupancy_slabs, "passes/occupancy_slabs");
        bits_program_ = link_program({&vs, &bits_fs}, "occupancy pass");
        slabs_program_ = link_program({&vs, &slabs_fs}, "slab pass");
    }

    /// The GLSL that defines float hs_transmittance(vec3 world_pos) for these maps: prepend a version
    /// line to it and bind the maps with bind_lookup().
    static std::string lookup_source() {
        std::string s = defines();
        for (auto piece : {accumulation_snippet(), shaders::placement_common, detail::placement_glsl<P>::snippet, detail::placement_glsl<P>::state,
                           shaders::reconstruction_occupancy_bitcount, shaders::lookup_light, shaders::lookup_occupancy_texels, shaders::lookup_occupancy})
            s += piece;
        return s;
    }

    /// Builds the maps of `mesh` seen from `light`.
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) {
        options.check(); // the CPU's rules: a NaN alpha is an error here too
        light_ = light;
        const int res = light.resolution();
        allocate(res);
        // 1. Depth range: per-texel states, and the global extent.
        range_.run(mesh, light, options);
        placement_.prepare(range_.extent());
        auto fbo = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        glViewport(0, 0, res, res);
        glDisable(GL_DEPTH_TEST);

        // 2. Occupancy bits: OR of each fragment's slice bit.
        glDisable(GL_BLEND);
        std::vector<GLuint> targets;
        for (auto& t : bits_) targets.push_back(t.get());
        attach(targets);
        const GLuint zero_u[4] = {0, 0, 0, 0};
        for (int i = 0; i < bit_targets; ++i) glClearBufferuiv(GL_COLOR, i, zero_u);
        glEnable(GL_COLOR_LOGIC_OP);
        glLogicOp(GL_OR);
        draw(bits_program_, mesh, light, options);
        glDisable(GL_COLOR_LOGIC_OP);

        // 3. Slabs: additive sums of optical depth.
        targets.clear();
        for (auto& t : slabs_) targets.push_back(t.get());
        attach(targets);
        const float zero_f[4] = {0, 0, 0, 0};
        for (int i = 0; i < slab_targets; ++i) glClearBufferfv(GL_COLOR, i, zero_f);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        draw(slabs_program_, mesh, light, options);
        glDisable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        check("occupancy maps build");
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename cpu_method::texel_maps> read_back() const {
        const int res = light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<typename A::value_type> slabs(4 * n * std::size_t(slab_targets));
        std::vector<std::uint32_t> bits(4 * n * std::size_t(bit_targets));
        for (int t = 0; t < bit_targets; ++t) {
            glBindTexture(GL_TEXTURE_2D, bits_[std::size_t(t)].get());
            glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, bits.data() + 4 * n * std::size_t(t));
        }
        for (int t = 0; t < slab_targets; ++t) {
            glBindTexture(GL_TEXTURE_2D, slabs_[std::size_t(t)].get());
            glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, eight_bit ? GL_UNSIGNED_BYTE : GL_FLOAT, slabs.data() + 4 * n * std::size_t(t));
        }
        check("occupancy maps read-back");
        std::vector<typename cpu_method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            auto& t = out[i];
            if (range_.empty(i)) continue; // no fragment: the CPU leaves the texel zero
            t.placement = detail::range_state{}.texel_state(placement_, range_, i);
            for (int w = 0; w < S / 32; ++w) t.data.bits[std::size_t(w)] = bits[4 * n * std::size_t(w / 4) + 4 * i + std::size_t(w % 4)];
            for (int s = 0; s < B; ++s) t.data.slabs[std::size_t(s)] = slabs[4 * n * std::size_t(s / 4) + 4 * i + std::size_t(s % 4)];
        }
        return out;
    }

    /// Binds the maps and the light for the look-up in program `prog`, on texture units from `first_unit`.
    void bind_lookup(GLuint prog, int first_unit = 0) const {
        set_lookup_uniforms(prog, light_, range_, first_unit);
        detail::placement_glsl<P>::set_uniforms(prog, placement_);
        int unit = first_unit + 1;
        auto bind = [&](const texture& t, const std::string& name) {
            glActiveTexture(GLenum(GL_TEXTURE0 + unit));
            glBindTexture(GL_TEXTURE_2D, t.get());
            glUniform1i(glGetUniformLocation(prog, name.c_str()), unit++);
        };
        for (int t = 0; t < bit_targets; ++t) bind(bits_[std::size_t(t)], "hs_bits_texture[" + std::to_string(t) + "]");
        for (int t = 0; t < slab_targets; ++t) bind(slabs_[std::size_t(t)], "hs_slabs_texture[" + std::to_string(t) + "]");
        glActiveTexture(GL_TEXTURE0);
    }

    const P& placement() const noexcept { return placement_; }
    const light_space& light() const noexcept { return light_; }
    /// Bytes of the textures the look-up reads: depth range (RGBA32F), occupancy bits (RGBA32UI) and
    /// slabs (RGBA32F or RGBA8), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t texels = std::size_t(allocated_) * std::size_t(allocated_);
        return texels * (16 + 16 * std::size_t(bit_targets) + (eight_bit ? 4 : 16) * std::size_t(slab_targets));
    }

    /// The maps read back as the CPU method, for CPU queries of maps built on GL.
    Method to_cpu() {
        Method cpu;
        cpu.adopt(light_, placement_, read_back());
        return cpu;
    }

private:
    static constexpr std::string_view version = "#version 430 core\n";
    static constexpr std::string_view accumulation_snippet() { return eight_bit ? shaders::accumulation_emulated_8bit : shaders::accumulation_float; }
    static std::string defines() {
        return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n#define HS_LAYERS " + std::to_string(S) +
               "\n#define HS_SLABS " + std::to_string(B) + "\n#define HS_BIT_TARGETS " + std::to_string(bit_targets) +
               "\n#define HS_SLAB_TARGETS " + std::to_string(slab_targets) + "\n" + detail::placement_glsl<P>::defines();
    }

    void allocate(int res) {
        if (res == allocated_) return;
        auto make = [&](GLenum format) { return make_texture_2d(format, res, res); };
        bits_.clear();
        slabs_.clear();
        for (int t = 0; t < bit_targets; ++t) bits_.push_back(make(GL_RGBA32UI));
        for (int t = 0; t < slab_targets; ++t) slabs_.push_back(make(eight_bit ? GL_RGBA8 : GL_RGBA32F));
        allocated_ = res;
    }

    static void attach(const std::vector<GLuint>& textures) {
        std::vector<GLenum> buffers;
        for (std::size_t i = 0; i < 8; ++i) glFramebufferTexture(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), i < textures.size() ? textures[i] : 0, 0);
        for (std::size_t i = 0; i < textures.size(); ++i) buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
        glDrawBuffers(GLsizei(buffers.size()), buffers.data());
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("occupancy maps: incomplete framebuffer");
    }

    void draw(const program& p, const hair_mesh& mesh, const light_space& light, const raster_options& options) const {
        glUseProgram(p.get());
        set_light_uniforms(p.get(), light, options);
        detail::placement_glsl<P>::set_uniforms(p.get(), placement_);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, range_.map().get());
        glUniform1i(glGetUniformLocation(p.get(), "hs_range_map"), 0);
        mesh.draw();
    }

    P placement_;
    light_space light_;
    int allocated_ = 0;
    depth_range_pass range_;
    program bits_program_, slabs_program_;
    std::vector<texture> bits_, slabs_;
};

} // namespace hairshadow::gl
