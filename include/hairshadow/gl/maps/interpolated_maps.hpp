#pragma once
/// @file
/// Interpolated methods on GL: opacity shadow maps (planar slices), deep opacity maps (per-pixel
/// depth), density clustering (clustered bins) and range opacity maps (depth range), float or
/// emulated 8-bit. The light pass (light_pass.hpp: MIN / MAX blending, then a GPU reduction) gives
/// every placement its per-texel state (z0; nearest and furthest) and the global depth extent;
/// density clustering adds its k-means passes (cluster_state_pass.hpp). Then additive passes write up
/// to 8 RGBA targets (32 layers) at a time into the layers of a 2D array texture (RGBA32F, or RGBA8
/// for 8 bits). Programs are composed from the same policy snippets whose CPU twins build the CPU maps.

#include <hairshadow/gl/maps/cluster_state_pass.hpp>
#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/passes/light_pass.hpp>
#include <hairshadow/gl/lookup/lookup_binding.hpp>
#include <hairshadow/gl/maps/policy_glsl.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/gl/context/state_guard.hpp>
#include <hairshadow/methods/published.hpp>

#include <array>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace hairshadow::gl {

namespace detail {
/// The program of a compute build pass: the shared compute snippets, the method's snippets, the pass.
inline program link_compute_pass(const std::string& defines, const std::vector<std::string_view>& snippets, std::string_view pass,
                                 const std::string& name) {
    auto pieces = compute_pieces(defines);
    pieces.insert(pieces.end(), snippets.begin(), snippets.end());
    pieces.push_back(pass);
    const auto s = compile_stage(GL_COMPUTE_SHADER, {}, pieces, name);
    return link_program({&s}, name);
}

/// What every GL method's maps share: the light pass they were built from (their own, or one shared
/// with other methods), its range textures, and the checks of the look-up's binding.
template <class P>
class maps_base {
public:
    const light_space& light() const noexcept { return light_; }
    /// The path build(mesh, light, options) takes from the next build on (build(pass) takes the
    /// pass's): at first default_build_path(), compute. Throws
    /// feature_error for compute where the context lacks what it needs.
    void set_build_path(build_path path) {
        if (path == build_path::compute) require_compute_path("the compute build path");
        path_ = path;
    }
    build_path path() const noexcept { return path_; }
    /// The placement as the CPU method's, prepared from the map's extent: the first call after a
    /// build reads the extent back (one texel, and a wait for the GPU).
    const P& placement() const {
        const auto& range = checked_range();
        if (prepared_generation_ != generation_) {
            placement_.prepare(read_extent(range));
            prepared_generation_ = generation_;
        }
        return placement_;
    }

protected:
    explicit maps_base(P placement) : placement_(std::move(placement)), path_(default_build_path()) {}

    /// The maps' own light pass, run for build(mesh, light, options), on the maps' path.
    const light_pass& own_pass(const hair_mesh& mesh, const light_space& light, const raster_options& options) {
        if (!own_pass_ || own_pass_->path() != path_) own_pass_ = std::make_unique<light_pass>(path_);
        own_pass_->run(mesh, light, options);
        return *own_pass_;
    }
    /// Takes the pass's textures and light for a build from it; the maps stay unusable until
    /// built() marks the build done, so that a build that throws leaves no maps that look valid.
    void adopt_pass(const light_pass& pass) {
        pass.mesh(); // throws if the pass has not run
        generation_ = 0;
        range_ = pass.textures();
        light_ = pass.light();
    }
    void built() noexcept { generation_ = range_->generation; }
    /// The range textures, if they still hold what these maps were built from.
    const range_textures& checked_range() const {
        if (!range_ || generation_ == 0) throw argument_error("the maps have not been built, or their last build failed");
        if (range_->generation != generation_)
            throw argument_error("the light pass these maps were built from has run again since: build them again from it");
        return *range_;
    }
    /// Makes `prog`, a compute pass over the light pass's lists, current, with its lists, uniforms
    /// and the range map bound (texture unit 0); the caller binds its output images and dispatches.
    void begin_compute_pass(const light_pass& pass, GLuint prog) const {
        glUseProgram(prog);
        pass.compute()->bind_for_tiles(prog);
        auto binder = lookup_binder::for_pass(prog, 0);
        binder.texture("hs_range_map", GL_TEXTURE_2D, range_->range.get());
        placement_glsl<P>::set_uniforms(binder, placement_);
    }
    /// The placement as constructed (the parameters its GLSL twin takes as uniforms), unprepared.
    const P& placement_spec() const noexcept { return placement_; }
    /// The CPU placement of the read-back range map `range`.
    const P& placement_from(const std::vector<float>& range) {
        placement_.prepare(extent_in_extra_row(range, range_->resolution));
        prepared_generation_ = generation_;
        return placement_;
    }
    /// Binds the range map and the light's frustum: the first texture unit of every look-up.
    void bind_light(lookup_binder& b) const {
        b.texture("hs_range_map", GL_TEXTURE_2D, checked_range().range.get());
        set_lookup_frustum(b, light_);
        placement_glsl<P>::set_uniforms(b, placement_);
    }

    std::shared_ptr<const range_textures> range_;
    std::uint64_t generation_ = 0;
    light_space light_;
    framebuffer fbo_ = make_framebuffer();

private:
    mutable P placement_;
    mutable std::uint64_t prepared_generation_ = 0;
    std::unique_ptr<light_pass> own_pass_;
    build_path path_;
};
} // namespace detail

/// GL twin of a shadow_method whose reconstruction is `interpolation` or one built on it, which stores
/// the same layers and changes only the look-up (hair_count): its GLSL follows interpolation's and
/// defines hs_optical_depth, with its defines and uniforms (gl/maps/policy_glsl.hpp). Any placement.
template <class Method>
class interpolated_maps_gl : public detail::maps_base<typename Method::placement_type> {
    using P = typename Method::placement_type;
    using A = typename Method::accumulation_type;
    using R = typename Method::reconstruction_type;
    using base = detail::maps_base<P>;
    using state_pass = typename placement_glsl<P>::state_pass;
    using accumulation = accumulation_glsl<A>;
    static_assert(std::is_base_of_v<interpolation, R>, "interpolated_maps_gl needs the interpolation reconstruction or one built on it");

public:
    static constexpr int layers = P::layer_count;
    static constexpr int array_layers = (layers + 3) / 4;
    /// RGBA layers of per-texel state beyond the depth range: density clustering's means and deviations, four each.
    static constexpr int state_targets = std::is_same_v<state_pass, detail::range_state> ? 0 : (layers + 3) / 4;
    /// Texture units the look-up reads (bind_lookup binds them from its first_unit): the range map,
    /// the layers, and density clustering's state.
    static constexpr int texture_units = 2 + state_pass::texture_units;

    /// Compiles the passes; throws feature_error if the context lacks GL 4.3 or 8 draw buffers.
    explicit interpolated_maps_gl(P placement = P(), R reconstruction = R()) : base(std::move(placement)), reconstruction_(std::move(reconstruction)) {
        require_version(4, 3, "interpolated shadow maps on GL");
        GLint draw_buffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
        targets_per_pass_ = std::min(std::min(draw_buffers, 8), array_layers);
        if (targets_per_pass_ < 1) throw feature_error("interpolated shadow maps need at least one draw buffer");
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
        const auto layers_fs = compile_stage(GL_FRAGMENT_SHADER, defines(targets_per_pass_),
                                             around_placement<P>({shaders::raster_coverage, accumulation::source(), shaders::arithmetic_exact_division, shaders::placement_common},
                                                                 {shaders::passes_layers}),
                                             "passes/layers");
        layers_program_ = link_program({&vs, &layers_fs}, "layers pass");
    }
    /// The same with `method`'s placement and reconstruction, and their parameters.
    explicit interpolated_maps_gl(const Method& method) : interpolated_maps_gl(method.placement(), method.reconstruction()) {}

    /// GLSL defining float hs_transmittance(vec3 world_pos), with every name under `prefix` (so
    /// "key_" defines key_transmittance): prepend a version line; bind with bind_lookup(program,
    /// first_unit, prefix). Any number of look-ups with different prefixes share one shader.
    static std::string lookup_source(std::string_view prefix = default_lookup_prefix) {
        std::string s = defines(1);
        for (auto piece : around_placement<P>({accumulation::source(), shaders::arithmetic_exact_division, shaders::placement_common},
                                              {shaders::lookup_layers, shaders::reconstruction_interpolation, reconstruction_source(), shaders::lookup_light,
                                               shaders::lookup_interpolation}))
            s += piece;
        return prefix_glsl(std::string(lookup_version_check) + s, prefix);
    }

    /// Builds the maps of `mesh` seen from `light`, with a light pass of their own.
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) { build(this->own_pass(mesh, light, options)); }

    /// Builds the maps from a light pass that has run (shared with other methods for the same light):
    /// its mesh, light and options. The maps read its range map: run it again, and build them again.
    void build(const light_pass& pass) {
        this->adopt_pass(pass);
        state_guard guard("hairshadow: interpolated maps");
        guard.set_pass_state();
        const int res = this->light_.resolution();
        allocate(res);
        const GLuint range = this->range_->range.get();
        if (pass.compute()) {
            build_compute(pass);
            check("interpolated maps: compute pass");
            this->built();
            return;
        }
        state_.run(pass.mesh(), this->light_, pass.options(), *this->range_, this->fbo_.get()); // density clustering's passes; nothing for the others

        // Layers, 4 per target, up to 8 targets a pass.
        glBindFramebuffer(GL_FRAMEBUFFER, this->fbo_.get());
        glViewport(0, 0, res, res);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(layers_program_.get());
        set_light_uniforms(layers_program_.get(), this->light_, pass.options());
        auto binder = lookup_binder::for_pass(layers_program_.get(), 0);
        binder.texture("hs_range_map", GL_TEXTURE_2D, range);
        placement_glsl<P>::set_uniforms(binder, this->placement_spec());
        state_.bind(binder);
        for (int base_layer = 0; base_layer < array_layers; base_layer += targets_per_pass_) {
            std::array<GLenum, 8> buffers{}; // no allocation in a frame
            GLsizei used_buffers = 0;
            for (int t = 0; t < 8; ++t) {
                const bool used = t < targets_per_pass_ && base_layer + t < array_layers;
                if (used) glFramebufferTextureLayer(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), layers_.get(), 0, base_layer + t);
                else glFramebufferTexture(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), 0, 0);
                if (used) buffers[std::size_t(used_buffers++)] = GLenum(GL_COLOR_ATTACHMENT0 + t);
            }
            glDrawBuffers(used_buffers, buffers.data());
            if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("interpolated maps: incomplete framebuffer");
            const float zero[4] = {0, 0, 0, 0};
            for (GLsizei t = 0; t < used_buffers; ++t) glClearBufferfv(GL_COLOR, t, zero);
            glUniform1i(glGetUniformLocation(layers_program_.get(), "hs_first_layer"), 4 * base_layer);
            pass.mesh().draw();
        }
        check("interpolated maps: layers pass");
        this->built();
    }

    /// Bytes of the textures the look-up reads: depth range (RGBA32F, one extra row), layers (RGBA32F
    /// or RGBA8) and density clustering's means and deviations (RGBA32F), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t texels = std::size_t(allocated_) * std::size_t(allocated_);
        return 16 * std::size_t(allocated_) * std::size_t(allocated_ + 1) +
               texels * (accumulation::texel_bytes * std::size_t(array_layers) + 16 * std::size_t(2 * state_targets));
    }

    /// The maps read back as the CPU method, for CPU queries of maps built on GL (with the
    /// reconstruction's parameters: hair_count's hair).
    Method to_cpu() {
        auto texels = read_back();
        Method cpu(this->placement(), reconstruction_);
        cpu.adopt(this->light_, this->placement(), std::move(texels));
        return cpu;
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename Method::texel_maps> read_back() {
        const auto range = detail::read_range(this->checked_range());
        const P& placement = this->placement_from(range);
        const int res = this->light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<typename A::value_type> stored(4 * n * std::size_t(array_layers));
        {
            state_guard guard("hairshadow: interpolated maps read-back");
            guard.set_pass_state();
            glBindTexture(GL_TEXTURE_2D_ARRAY, layers_.get());
            glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA, accumulation::pixel_type, stored.data());
            check("interpolated maps read-back");
            state_.read_back();
        }
        std::vector<typename Method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            const float* texel_range = &range[4 * i];
            if (texel_range[0] > texel_range[3]) continue; // no fragment: the CPU leaves the texel zero
            out[i].placement = state_.texel_state(placement, texel_range, i);
            for (int k = 0; k < layers; ++k)
                out[i].data.layers[std::size_t(k)] = stored[4 * n * std::size_t(k / 4) + 4 * i + std::size_t(k % 4)];
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
        binder.texture("hs_layers_texture", GL_TEXTURE_2D_ARRAY, layers_.get());
        state_.bind(binder);
        detail::set_policy_uniforms(binder, reconstruction_);
    }

private:
    static std::string defines(int targets) {
        return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n#define HS_LAYERS " + std::to_string(layers) +
               "\n#define HS_LAYER_TARGETS " + std::to_string(targets) + "\n" + (P::cumulative ? "#define HS_CUMULATIVE\n" : "") +
               accumulation::defines() + placement_glsl<P>::defines() + detail::policy_defines<R>();
    }
    /// A reconstruction built on interpolation brings its look-up's GLSL; interpolation's own is above.
    static std::string_view reconstruction_source() {
        if constexpr (std::is_same_v<R, interpolation>) return {};
        else return detail::policy_source<R>(R::glsl_name);
    }
    void allocate(int res) {
        if (res == allocated_) return;
        layers_ = make_texture();
        glBindTexture(GL_TEXTURE_2D_ARRAY, layers_.get());
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, accumulation::texture_format, res, res, array_layers);
        allocated_ = res;
    }

    /// The compute build, one work group per tile of the light pass's lists: shaders/compute/layers,
    /// or for density clustering shaders/compute/clusters, which also writes the cluster state.
    void build_compute(const light_pass& pass) {
        const GLuint prog = compute_program_.for_run(*pass.compute(), [](const std::string& alpha) { return link_compute_program(alpha); });
        this->begin_compute_pass(pass, prog);
        glBindImageTexture(0, layers_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, accumulation::texture_format);
        if constexpr (!range_placement<P>)
            glBindImageTexture(1, state_.state_texture(this->light_.resolution()), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        pass.compute()->dispatch_tiles();
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    }
    static program link_compute_program(const std::string& alpha) {
        const std::string format = accumulation::image_defines("HS_LAYERS_FORMAT");
        if constexpr (range_placement<P>) {
            // Layers summed per walk: 8 bytes a sum (4 for 8-bit steps), beside the texels' ranges.
            const int group = detail::sums_per_walk(layers, accumulation::unorm8 ? 4 : 8, detail::compute_tile * detail::compute_tile * 8);
            return detail::link_compute_pass(alpha + defines(1) + format + "#define HS_LAYER_GROUP " + std::to_string(group) + "\n#define HS_SUM_SLOTS " +
                                                 std::to_string(group) + "\n",
                                             around_placement<P>({accumulation::source(), shaders::compute_tile_sums, shaders::arithmetic_exact_division, shaders::placement_common}, {}),
                                             shaders::compute_layers, "compute/layers");
        } else {
            // Strips of the tile whose k-means sums (four words a cluster) and state (a mean and a
            // deviation) fit the context's shared memory (32 KiB at least: one strip up to K = 5).
            const int rows = detail::strip_rows(6 * layers * 4);
            return detail::link_compute_pass(alpha + defines(1) + format + "#define HS_FIXED_SUMS\n#define HS_SUM_SLOTS " + std::to_string(2 * layers) +
                                                 "\n#define HS_STRIP_ROWS " + std::to_string(rows) + "\n#define HS_SUM_TEXELS " +
                                                 std::to_string(detail::compute_tile * rows) + "\n",
                                             {accumulation::source(), shaders::compute_tile_sums, shaders::arithmetic_exact_division, shaders::arithmetic_exact_square_root,
                                              shaders::placement_common, placement_glsl<P>::sources().front()},
                                             shaders::compute_clusters, "compute/clusters");
        }
    }

    R reconstruction_;
    int allocated_ = 0, targets_per_pass_ = 1;
    state_pass state_;
    program layers_program_;
    detail::compute_pass_program compute_program_;
    texture layers_;
};

} // namespace hairshadow::gl
