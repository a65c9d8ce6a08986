#pragma once
/// @file
/// The pre-pass every GL method starts with (Sintorn & Assarsson 2009, section 3.1): each texel's
/// nearest fragment under MIN blending (red) and furthest under MAX blending (alpha), then the whole
/// map's depth extent reduced from it on the GPU by two compute dispatches, so no build reads anything
/// back. That is build_path::raster; on build_path::compute the pass prepares and bins the segments
/// on the GPU instead (compute_raster.hpp), writes the same range map from the CPU's fragments and
/// takes the extent from the segments' ends, as the CPU does; the maps built from it walk its lists.
/// Several methods for one light and one mesh share one light_pass: run it, then build each method's
/// maps from it.

#include <hairshadow/gl/passes/compute_raster.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/gl/context/state_guard.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace hairshadow::gl {

namespace detail {
/// A light pass's textures, shared with the maps built from it: their passes and look-ups read them.
struct range_textures {
    /// RGBA32F, res wide and res + 1 tall: rows [0, res) the range map (nearest in red, furthest in
    /// alpha; red > alpha where no fragment fell); row res, texel 0: the map's extent (nearest, 0, 0,
    /// furthest; zero for an empty map), read by placement/common's hs_map_extent.
    texture range;
    /// The extent of each 64x64 tile of the range map, the first dispatch's output.
    texture tiles;
    int resolution = 0;
    /// Which run of any light pass filled them (from next_generation): maps built from an earlier run
    /// refuse to bind after a later one.
    std::uint64_t generation = 0;
};

/// A number no earlier call returned, never 0 (which marks maps not, or not wholly, built).
inline std::uint64_t next_generation() noexcept {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

inline constexpr int extent_tile = 64; // the texels a work group of passes/depth_extent.glsl reduces, per side

/// A program that draws the hair mesh's lines with a fragment pass that needs only each fragment's
/// depth and optical depth (raster/coverage): the depth-range pass, the fibre count.
inline program link_line_pass(std::string_view pass_snippet, const std::string& name) {
    const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::raster_vertex}, "raster/vertex");
    const auto fs = compile_stage(GL_FRAGMENT_SHADER, {},
                                   {"#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n", shaders::raster_coverage, pass_snippet},
                                   name);
    return link_program({&vs, &fs}, name);
}
} // namespace detail

/// The depth-range map and depth extent of one hair mesh seen from one light.
class light_pass {
public:
    /// Compiles the passes of `path` (by default compute); throws feature_error without GL 4.3, or
    /// for compute where the context lacks what it needs (compute_path_missing()).
    light_pass() : light_pass(default_build_path()) {}
    explicit light_pass(build_path path) : path_(path) {
        require_version(4, 3, "the GL light pass");
        if (path == build_path::compute) {
            compute_ = std::make_unique<detail::compute_segments>();
            return;
        }
        range_program_ = detail::link_line_pass(shaders::passes_depth_range, "depth-range pass");
        const auto tiles = compile_stage(GL_COMPUTE_SHADER, {}, {"#define HS_EXTENT_TILES\n", shaders::passes_depth_extent}, "passes/depth_extent tiles");
        const auto whole = compile_stage(GL_COMPUTE_SHADER, {}, {shaders::passes_depth_extent}, "passes/depth_extent");
        tiles_program_ = link_program({&tiles}, "depth-extent pass (tiles)");
        extent_program_ = link_program({&whole}, "depth-extent pass");
    }

    /// Draws the range map of `mesh` seen from `light` and reduces its extent, all on the GPU. The
    /// pass keeps a pointer to `mesh` (which must stay where it is): the maps built from it draw it.
    void run(const hair_mesh&& mesh, const light_space& light, const raster_options& options = {}) = delete;
    void run(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) {
        options.check();
        state_guard guard("hairshadow: light pass");
        guard.set_pass_state();
        const int res = light.resolution();
        allocate(res);
        textures_->generation = detail::next_generation();
        mesh_ = &mesh;
        light_ = light;
        options_ = options;
        if (compute_) {
            compute_->run(mesh, light, options, textures_->range.get());
            // Later passes fetch the range map or walk the lists, read-backs copy it.
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                            GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            check("light pass: compute build");
            return;
        }

        // 1. Nearest and furthest fragment of each texel.
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
        glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, textures_->range.get(), 0);
        const GLenum first = GL_COLOR_ATTACHMENT0;
        glDrawBuffers(1, &first);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("light pass: incomplete framebuffer");
        glViewport(0, 0, res, res);
        const float clear[4] = {3.0e38f, 0.0f, 0.0f, -3.0e38f};
        glClearBufferfv(GL_COLOR, 0, clear);
        glEnable(GL_BLEND);
        glBlendEquationSeparate(GL_MIN, GL_MAX);
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(range_program_.get());
        set_light_uniforms(range_program_.get(), light, options);
        mesh.draw();
        glDisable(GL_BLEND);
        check("light pass: depth range");

        // 2. The extent: each 64x64 tile's, then the whole map's, written into the range map's extra row.
        const int tiles = (res + detail::extent_tile - 1) / detail::extent_tile;
        glBindTexture(GL_TEXTURE_2D, textures_->range.get());
        glUseProgram(tiles_program_.get());
        glUniform2i(glGetUniformLocation(tiles_program_.get(), "hs_input_size"), res, res);
        glBindImageTexture(0, textures_->tiles.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(GLuint(tiles), GLuint(tiles), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        glBindTexture(GL_TEXTURE_2D, textures_->tiles.get());
        glUseProgram(extent_program_.get());
        glUniform2i(glGetUniformLocation(extent_program_.get(), "hs_input_size"), tiles, tiles);
        glUniform2i(glGetUniformLocation(extent_program_.get(), "hs_extent_texel"), 0, res);
        glBindImageTexture(0, textures_->range.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(1, 1, 1);
        // Later passes fetch it, a later run clears it as a render target, read-backs copy it.
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        check("light pass: depth extent");
    }

    bool has_run() const noexcept { return mesh_ != nullptr; }
    /// The mesh, light and options of the last run; mesh() throws before the first.
    const hair_mesh& mesh() const {
        if (!mesh_) throw argument_error("the light pass has not run: call run(mesh, light) first");
        return *mesh_;
    }
    const light_space& light() const noexcept { return light_; }
    const raster_options& options() const noexcept { return options_; }
    /// How this pass, and the maps built from it, are built.
    build_path path() const noexcept { return path_; }
    /// The prepared and binned segments of the last run, on build_path::compute (else null).
    const detail::compute_segments* compute() const noexcept { return compute_.get(); }
    /// The textures of the last run (shared: maps built from it keep them alive).
    const std::shared_ptr<detail::range_textures>& textures() const noexcept { return textures_; }

private:
    void allocate(int res) {
        if (textures_ && textures_->resolution == res) return;
        // New textures: maps still holding the old ones keep them, with the generation they were built from.
        textures_ = std::make_shared<detail::range_textures>();
        textures_->range = make_texture_2d(GL_RGBA32F, res, res + 1);
        const int tiles = (res + detail::extent_tile - 1) / detail::extent_tile;
        textures_->tiles = make_texture_2d(GL_RGBA32F, tiles, tiles);
        textures_->resolution = res;
    }

    build_path path_;
    std::unique_ptr<detail::compute_segments> compute_;
    program range_program_, tiles_program_, extent_program_;
    framebuffer fbo_ = make_framebuffer();
    std::shared_ptr<detail::range_textures> textures_;
    const hair_mesh* mesh_ = nullptr;
    light_space light_;
    raster_options options_;
};

namespace detail {
/// The range map of `t` read back: 4 floats per texel, rows [0, res) then the extent row.
inline std::vector<float> read_range(const range_textures& t) {
    state_guard guard("hairshadow: range read-back");
    guard.set_pass_state();
    std::vector<float> values(4 * std::size_t(t.resolution) * std::size_t(t.resolution + 1));
    glBindTexture(GL_TEXTURE_2D, t.range.get());
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, values.data());
    check("range read-back");
    return values;
}

/// The map's extent alone: one texel read back.
inline depth_extent read_extent(const range_textures& t) {
    state_guard guard("hairshadow: extent read-back");
    guard.set_pass_state();
    const auto fbo = make_framebuffer();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.get());
    glFramebufferTexture(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, t.range.get(), 0);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    float e[4] = {0, 0, 0, 0};
    glReadPixels(0, t.resolution, 1, 1, GL_RGBA, GL_FLOAT, e);
    check("extent read-back");
    return {e[0], e[3]};
}

/// The map's extent from a read-back range map (its extra row).
inline depth_extent extent_in_extra_row(const std::vector<float>& range, int res) {
    const float* e = &range[4 * std::size_t(res) * std::size_t(res)];
    return {e[0], e[3]};
}
} // namespace detail

} // namespace hairshadow::gl
