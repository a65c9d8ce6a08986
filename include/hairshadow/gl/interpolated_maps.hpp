#pragma once
/// @file
/// Interpolated methods on GL: opacity shadow maps (planar slices), deep opacity maps (per-pixel
/// depth), density clustering (clustered bins) and range opacity maps (depth range), float or
/// emulated 8-bit. A depth-range pass (MIN / MAX blending) gives every placement its per-texel state
/// (z0; nearest and furthest) and, reduced on the CPU, the global depth extent; density clustering
/// adds its k-means passes (cluster_state_pass.hpp). Then additive passes write up to 8 RGBA targets
/// (32 layers) at a time into the layers of a 2D array texture (RGBA32F, or RGBA8 for 8 bits).
/// Programs are composed from the same policy snippets whose CPU twins build the CPU maps.

#include <hairshadow/gl/cluster_state_pass.hpp>
#include <hairshadow/gl/context.hpp>
#include <hairshadow/gl/depth_range_pass.hpp>
#include <hairshadow/gl/hair_mesh.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/methods/published.hpp>

#include <string>
#include <type_traits>
#include <vector>

namespace hairshadow::gl {

namespace detail {
/// The per-texel state of placements whose state is the depth range's: nothing more to draw.
struct range_state {
    static std::string defines() { return ""; }
    void run(const hair_mesh&, const light_space&, const raster_options&, const depth_range_pass&) {}
    void bind(GLuint, int) const {}
    void read_back() {}
    /// The CPU texel state, from a depth-range texel (nearest in [0], furthest in [3]).
    template <class P>
    typename P::texel_state texel_state(const P& placement, const depth_range_pass& range, std::size_t i) const {
        typename P::texel_state s{};
        const fragment pair[2] = {{range.texel(i)[0], 0.0f}, {range.texel(i)[3], 0.0f}};
        placement.prepare_texel(std::span<const fragment>(pair, 2), s); // the state's own pre-pass, on the two extremes
        return s;
    }
};

template <class P>
struct placement_glsl; // what a placement needs on GL

template <int N, class Spacing>
struct placement_glsl<planar_slices<N, Spacing>> {
    using state_pass = range_state;
    static std::string defines() { return std::is_same_v<Spacing, gamma_spacing> ? "#define HS_GAMMA_SPACING\n" : ""; }
    static constexpr std::string_view snippet = shaders::placement_planar_slices, state = shaders::texel_state_planar_slices;
    static void set_uniforms(GLuint prog, const planar_slices<N, Spacing>& p) {
        glUniform1f(glGetUniformLocation(prog, "hs_slices_near"), p.nearest());
        glUniform1f(glGetUniformLocation(prog, "hs_slices_far"), p.furthest());
    }
};

template <int K, layer_sizes Sizes, beyond_last_layer Beyond>
struct placement_glsl<per_pixel_depth<K, Sizes, Beyond>> {
    using P = per_pixel_depth<K, Sizes, Beyond>;
    using state_pass = range_state;
    static std::string defines() {
        return std::string(Sizes == layer_sizes::uniform ? "#define HS_UNIFORM_SIZES\n" : "") +
               (Beyond == beyond_last_layer::ignore ? "#define HS_BEYOND_IGNORE\n" : "") +
               (Beyond == beyond_last_layer::extend ? "#define HS_BEYOND_EXTEND\n" : "");
    }
    static constexpr std::string_view snippet = shaders::placement_per_pixel_depth, state = shaders::texel_state_per_pixel_depth;
    static void set_uniforms(GLuint prog, const P& p) { glUniform1f(glGetUniformLocation(prog, "hs_layer_extent"), p.extent()); }
};

template <int S>
struct placement_glsl<depth_range<S>> {
    using state_pass = range_state;
    static std::string defines() { return ""; }
    static constexpr std::string_view snippet = shaders::placement_depth_range, state = shaders::texel_state_depth_range;
    static void set_uniforms(GLuint, const depth_range<S>&) {}
};

template <int K>
struct placement_glsl<clustered<K>> {
    using state_pass = cluster_state_pass<K>;
    static std::string defines() { return state_pass::defines(); }
    static constexpr std::string_view snippet = shaders::placement_clustered, state = shaders::texel_state_clustered;
    static void set_uniforms(GLuint, const clustered<K>&) {}
};
} // namespace detail

/// GL twin of a shadow_method whose reconstruction is `interpolation` (any placement).
template <class Method>
class interpolated_maps_gl {
    using P = typename Method::placement_type;
    using A = typename Method::accumulation_type;
    static_assert(std::is_same_v<typename Method::reconstruction_type, interpolation>, "interpolated_maps_gl needs the interpolation reconstruction");
    static constexpr bool eight_bit = std::is_same_v<A, emulated_8bit>;

public:
    static constexpr int layers = P::layer_count;
    static constexpr int array_layers = (layers + 3) / 4;
    /// RGBA layers of per-texel state beyond the depth range: density clustering's means and deviations, four each.
    static constexpr int state_targets = std::is_same_v<typename detail::placement_glsl<P>::state_pass, detail::range_state> ? 0 : (layers + 3) / 4;

    /// Compiles the passes; throws feature_error if the context lacks GL 4.3 or 8 draw buffers.
    explicit interpolated_maps_gl(P placement = P()) : placement_(std::move(placement)) {
        require_version(4, 3, "interpolated shadow maps on GL");
        GLint draw_buffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
        targets_per_pass_ = std::min(std::min(draw_buffers, 8), array_layers);
        if (targets_per_pass_ < 1) throw feature_error("interpolated shadow maps need at least one draw buffer");
        const auto vs = compile_shader(GL_VERTEX_SHADER, {version, shaders::raster_vertex}, "raster/vertex");
        const auto layers_fs = compile_shader(GL_FRAGMENT_SHADER,
                                              {version, defines(targets_per_pass_), shaders::raster_coverage, accumulation_snippet(),
                                               shaders::placement_common, detail::placement_glsl<P>::snippet, detail::placement_glsl<P>::state,
                                               shaders::passes_layers},
                                              "passes/layers");
        layers_program_ = link_program({&vs, &layers_fs}, "layers pass");
    }

    /// GLSL defining float hs_transmittance(vec3 world_pos); prepend a version line, bind with bind_lookup().
    std::string lookup_source() const {
        std::string s = defines(1);
        for (auto piece : {accumulation_snippet(), shaders::placement_common, detail::placement_glsl<P>::snippet,
                           detail::placement_glsl<P>::state, shaders::lookup_layers, shaders::reconstruction_interpolation, shaders::lookup_light,
                           shaders::lookup_interpolation})
            s += piece;
        return s;
    }

    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) {
        options.check(); // the CPU's rules: a NaN alpha is an error here too
        light_ = light;
        const int res = light.resolution();
        allocate(res);
        // 1. Depth range: per-texel states, and the global extent.
        range_.run(mesh, light, options);
        placement_.prepare(range_.extent());
        state_.run(mesh, light, options, range_); // density clustering's passes; nothing for the others
        auto fbo = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        glViewport(0, 0, res, res);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);

        // 2. Layers, 4 per target, up to 8 targets a pass.
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(layers_program_.get());
        set_light_uniforms(layers_program_.get(), light, options);
        detail::placement_glsl<P>::set_uniforms(layers_program_.get(), placement_);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, range_.map().get());
        glUniform1i(glGetUniformLocation(layers_program_.get(), "hs_range_map"), 0);
        state_.bind(layers_program_.get(), 1);
        for (int base = 0; base < array_layers; base += targets_per_pass_) {
            std::vector<GLenum> buffers;
            for (int t = 0; t < 8; ++t) {
                const bool used = t < targets_per_pass_ && base + t < array_layers;
                if (used) glFramebufferTextureLayer(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), layers_.get(), 0, base + t);
                else glFramebufferTexture(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), 0, 0);
                if (used) buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + t));
            }
            glDrawBuffers(GLsizei(buffers.size()), buffers.data());
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("interpolated maps: incomplete framebuffer");
            const float zero[4] = {0, 0, 0, 0};
            for (std::size_t t = 0; t < buffers.size(); ++t) glClearBufferfv(GL_COLOR, GLint(t), zero);
            glUniform1i(glGetUniformLocation(layers_program_.get(), "hs_first_layer"), 4 * base);
            mesh.draw();
        }
        glDisable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        check("interpolated maps build");
    }

    const P& placement() const noexcept { return placement_; }
    const light_space& light() const noexcept { return light_; }
    /// Bytes of the textures the look-up reads: depth range (RGBA32F), layers (RGBA32F or RGBA8) and
    /// density clustering's means and deviations (RGBA32F), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t texels = std::size_t(allocated_) * std::size_t(allocated_);
        return texels * (16 + (eight_bit ? 4 : 16) * std::size_t(array_layers) + 16 * std::size_t(2 * state_targets));
    }

    /// The maps read back as the CPU method, for CPU queries of maps built on GL.
    Method to_cpu() {
        Method cpu;
        cpu.adopt(light_, placement_, read_back());
        return cpu;
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename Method::texel_maps> read_back() {
        const int res = light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<typename A::value_type> stored(4 * n * std::size_t(array_layers));
        glBindTexture(GL_TEXTURE_2D_ARRAY, layers_.get());
        glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA, eight_bit ? GL_UNSIGNED_BYTE : GL_FLOAT, stored.data());
        check("interpolated maps read-back");
        state_.read_back();
        std::vector<typename Method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            if (range_.empty(i)) continue; // no fragment: the CPU leaves the texel zero
            out[i].placement = state_.texel_state(placement_, range_, i);
            for (int k = 0; k < layers; ++k)
                out[i].data.layers[std::size_t(k)] = stored[4 * n * std::size_t(k / 4) + 4 * i + std::size_t(k % 4)];
        }
        return out;
    }

    /// Binds the maps and the light for the look-up in program `prog`, on texture units
    /// [first_unit, first_unit + 3).
    void bind_lookup(GLuint prog, int first_unit = 0) const {
        set_lookup_uniforms(prog, light_, range_, first_unit);
        detail::placement_glsl<P>::set_uniforms(prog, placement_);
        glActiveTexture(GLenum(GL_TEXTURE0 + first_unit + 1));
        glBindTexture(GL_TEXTURE_2D_ARRAY, layers_.get());
        glUniform1i(glGetUniformLocation(prog, "hs_layers_texture"), first_unit + 1);
        glActiveTexture(GL_TEXTURE0);
        state_.bind(prog, first_unit + 2);
    }

private:
    static constexpr std::string_view version = "#version 430 core\n";
    static constexpr std::string_view accumulation_snippet() { return eight_bit ? shaders::accumulation_emulated_8bit : shaders::accumulation_float; }
    static std::string defines(int targets) {
        return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n#define HS_LAYERS " + std::to_string(layers) +
               "\n#define HS_LAYER_TARGETS " + std::to_string(targets) + "\n" + (P::cumulative ? "#define HS_CUMULATIVE\n" : "") +
               detail::placement_glsl<P>::defines();
    }
    void allocate(int res) {
        if (res == allocated_) return;
        layers_ = make_texture();
        glBindTexture(GL_TEXTURE_2D_ARRAY, layers_.get());
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, eight_bit ? GL_RGBA8 : GL_RGBA32F, res, res, array_layers);
        allocated_ = res;
    }

    P placement_;
    light_space light_;
    int allocated_ = 0, targets_per_pass_ = 1;
    depth_range_pass range_;
    typename detail::placement_glsl<P>::state_pass state_;
    program layers_program_;
    texture layers_;
};

} // namespace hairshadow::gl
