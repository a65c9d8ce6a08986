#pragma once
/// @file
/// Adaptive volumetric shadow maps on GL (a reconstruction of adaptive_nodes): as the paper builds
/// them, every fragment is first appended to its texel's list (the compute path's walk of the light
/// pass's tiles, or the raster path's fragments; shaders/passes/fragment_lists.glsl), then one
/// invocation per texel takes its list in (depth, optical depth) order into at most N nodes
/// (shaders/compute/resolve_nodes.glsl), written two to a layer of an RGBA32F 2D array texture. The
/// order comes from the fragments' values alone, so the compute path gives the CPU's maps bit for
/// bit. The lists' buffer grows to the fragments a build makes: a build whose fragments outgrow it
/// walks once more.

#include <hairshadow/gl/maps/interpolated_maps.hpp>
#include <hairshadow/reconstruction/adaptive_nodes.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace hairshadow::gl {

/// GL twin of a shadow_method whose reconstruction is adaptive_nodes<N>.
template <class Method>
class node_maps_gl : public detail::maps_base<typename Method::placement_type> {
    using P = typename Method::placement_type;
    using R = typename Method::reconstruction_type;
    using base = detail::maps_base<P>;

public:
    static constexpr int nodes = R::node_count;
    static constexpr int array_layers = (nodes + 1) / 2;
    /// Texture units the look-up reads (bind_lookup binds them from its first_unit): the range map and the nodes.
    static constexpr int texture_units = 2;

    /// Throws feature_error without GL 4.3.
    explicit node_maps_gl(const Method& method = Method()) : base(method.placement()) { require_version(4, 3, "adaptive volumetric shadow maps on GL"); }

    /// GLSL defining float hs_transmittance(vec3 world_pos), with every name under `prefix`: prepend a
    /// version line; bind with bind_lookup(program, first_unit, prefix).
    static std::string lookup_source(std::string_view prefix = default_lookup_prefix) {
        std::string s = defines();
        for (auto piece : {shaders::arithmetic_exact_division, shaders::placement_common, shaders::reconstruction_adaptive_nodes, shaders::lookup_light, shaders::lookup_nodes}) s += piece;
        return prefix_glsl(std::string(lookup_version_check) + s, prefix);
    }

    /// Builds the maps of `mesh` seen from `light`, with a light pass of their own.
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) { build(this->own_pass(mesh, light, options)); }

    /// Builds the maps from a light pass that has run (shared with other methods for the same light).
    void build(const light_pass& pass) {
        this->adopt_pass(pass);
        state_guard guard("hairshadow: adaptive nodes");
        guard.set_pass_state();
        const int res = this->light_.resolution();
        allocate(res);
        // The lists: a walk, and another if the fragments outgrew the buffer.
        for (int walk = 0; walk < 2; ++walk) {
            const std::uint32_t empty_list[2] = {0xffffffffu, 0u}, zero[2] = {0u, 0u}; // no first record, no length; no records, no status
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, heads_.get());
            glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, empty_list);
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, records_.get());
            glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
            list_fragments(pass);
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
            std::uint32_t listed = 0;
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, records_.get());
            glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, 4, &listed);
            last_fragments_ = listed;
            if (listed <= capacity_) break;
            if (walk == 1) throw gl_error("adaptive nodes: the second walk made more fragments than the first");
            grow_records(listed);
        }
        // The nodes.
        if (!resolve_program_) { // a pass over texels, not tiles: none of compute/common
            const auto s = compile_stage(GL_COMPUTE_SHADER, defines(),
                                         {shaders::passes_fragment_lists, shaders::reconstruction_adaptive_nodes, shaders::compute_resolve_nodes},
                                         "compute/resolve_nodes");
            resolve_program_ = link_program({&s}, "compute/resolve_nodes");
        }
        glUseProgram(resolve_program_.get());
        glUniform1i(glGetUniformLocation(resolve_program_.get(), "hs_resolution"), res);
        glUniform1i(glGetUniformLocation(resolve_program_.get(), "hs_probe_steps"), 2);
        bind_lists();
        glBindImageTexture(0, nodes_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const GLuint groups = GLuint((res + 7) / 8);
        glDispatchCompute(groups, groups, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        check("adaptive nodes: resolve pass");
        std::uint32_t status = 0;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, records_.get());
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 4, 4, &status);
        if (status != 0)
            throw gl_error("adaptive nodes: this GL implementation stopped the resolve pass's loops early (Mesa's llvmpipe ends a shader's loops after "
                           "65535 steps), so a texel's fragments were not all inserted: build these maps on the CPU, at a higher resolution, or on a GPU");
        this->built();
    }

    /// Reads the maps back in the CPU method's texel layout.
    std::vector<typename Method::texel_maps> read_back() {
        const auto range = detail::read_range(this->checked_range());
        (void)this->placement_from(range);
        const int res = this->light_.resolution();
        const std::size_t n = std::size_t(res) * std::size_t(res);
        std::vector<float> stored(4 * n * std::size_t(array_layers));
        {
            state_guard guard("hairshadow: adaptive nodes read-back");
            guard.set_pass_state();
            glBindTexture(GL_TEXTURE_2D_ARRAY, nodes_.get());
            glGetTexImage(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA, GL_FLOAT, stored.data());
            check("adaptive nodes read-back");
        }
        std::vector<typename Method::texel_maps> out(n);
        for (std::size_t i = 0; i < n; ++i)
            for (int k = 0; k < nodes; ++k) {
                const float* v = &stored[4 * n * std::size_t(k / 2) + 4 * i + 2 * std::size_t(k % 2)];
                out[i].data.nodes[std::size_t(k)] = {v[0], v[1]};
            }
        return out;
    }

    /// The maps read back as the CPU method, for CPU queries.
    Method to_cpu() {
        auto texels = read_back();
        Method cpu(this->placement());
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
        binder.texture("hs_nodes_texture", GL_TEXTURE_2D_ARRAY, nodes_.get());
    }

    /// Bytes of the textures the look-up reads: the depth range (RGBA32F, one extra row) and the
    /// nodes (8 bytes each), at the last build's resolution.
    std::size_t memory_bytes() const noexcept {
        const std::size_t res = std::size_t(allocated_);
        return 16 * res * (res + 1) + 16 * res * res * std::size_t(array_layers);
    }
    /// Bytes of the build's working memory: the lists' heads and records.
    std::size_t working_bytes() const noexcept { return 8 * std::size_t(allocated_) * std::size_t(allocated_) + 8 + 12 * capacity_; }
    /// Fragments the last build listed.
    std::size_t fragment_count() const noexcept { return last_fragments_; }

private:
    static std::string defines() { return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n" + R::glsl_defines(); }

    /// Appends every fragment of the pass to its texel's list.
    void list_fragments(const light_pass& pass) {
        if (pass.compute()) {
            const GLuint prog = list_program_.for_run(*pass.compute(), [](const std::string& alpha) {
                return detail::link_compute_pass(alpha + defines(), {shaders::passes_fragment_lists}, shaders::compute_fragment_lists, "compute/fragment_lists");
            });
            this->begin_compute_pass(pass, prog);
            bind_lists();
            pass.compute()->dispatch_tiles();
            return;
        }
        if (!raster_program_) {
            GLint blocks = 0;
            glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &blocks);
            if (blocks < 2) throw feature_error("adaptive volumetric shadow maps' raster path needs 2 shader storage blocks in fragment shaders");
            const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
            const auto fs = compile_stage(GL_FRAGMENT_SHADER, defines(), {shaders::raster_coverage, shaders::passes_fragment_lists, shaders::passes_list_raster},
                                          "passes/list_raster");
            raster_program_ = link_program({&vs, &fs}, "list pass");
        }
        const int res = this->light_.resolution();
        glBindFramebuffer(GL_FRAMEBUFFER, this->fbo_.get()); // no attachments: its default size
        glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, res);
        glFramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, res);
        glViewport(0, 0, res, res);
        glDisable(GL_BLEND);
        glUseProgram(raster_program_.get());
        set_light_uniforms(raster_program_.get(), this->light_, pass.options());
        glUniform1i(glGetUniformLocation(raster_program_.get(), "hs_resolution"), res);
        bind_lists();
        pass.mesh().draw();
        check("adaptive nodes: list pass");
    }

    void bind_lists() const {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, heads_.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, records_.get());
    }

    /// Room for `records` fragments (12 bytes each after the count and the status), within one storage block.
    void grow_records(std::size_t records) {
        GLint64 block = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
        const double bytes = 8.0 + 12.0 * double(records);
        if (bytes > double(block))
            throw feature_error("adaptive volumetric shadow maps list " + std::to_string(records) + " fragments in one shader storage block: " +
                                std::to_string(std::uint64_t(bytes)) + " bytes, more than this context's " + std::to_string(block));
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, records_.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_COPY);
        capacity_ = records;
    }

    void allocate(int res) {
        if (capacity_ == 0) { // a first guess of 4 fragments a texel, within one storage block; a build that needs more grows it
            GLint64 block = 0;
            glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
            grow_records(std::min<std::size_t>(4 * std::size_t(res) * std::size_t(res), std::size_t(std::max<GLint64>(block - 8, 12) / 12)));
        }
        if (res == allocated_) return;
        nodes_ = make_texture();
        glBindTexture(GL_TEXTURE_2D_ARRAY, nodes_.get());
        glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32F, res, res, array_layers);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, heads_.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(8 * std::size_t(res) * std::size_t(res)), nullptr, GL_DYNAMIC_COPY);
        allocated_ = res;
    }

    int allocated_ = 0;
    std::size_t capacity_ = 0, last_fragments_ = 0;
    program raster_program_, resolve_program_;
    detail::compute_pass_program list_program_;
    texture nodes_;
    buffer heads_ = make_buffer(), records_ = make_buffer();
};

} // namespace hairshadow::gl
