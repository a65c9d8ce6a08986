#pragma once
/// @file
/// The compute build's shared half: the hair mesh's segments prepared, binned and walked on the GPU
/// by compute shaders (shaders/compute/), with exactly the CPU rasteriser's arithmetic, so that the
/// maps built from them hold the CPU maps' fragments, not the GL driver's. A light pass on
/// build_path::compute runs it: prepare (transform, clip, snap; count tiles; the map's extent), scan
/// (tile offsets), scatter (segment lists per 16x16 tile), then the range map, one work group per tile.
/// Each method's compute pass then walks the same lists (interpolated_maps.hpp, occupancy_maps.hpp).
/// Sums are taken in fixed point, so no result depends on the order the GPU runs anything in.

#include <hairshadow/config.hpp>
#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/gl/context/state_guard.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hairshadow::gl {

/// How GL maps are built.
enum class build_path {
    compute, ///< compute shaders walk the CPU's line rule tile by tile: the CPU's fragments, no blending
    raster,  ///< the papers' passes: GL lines drawn into blended targets, the driver's fragments
};

inline std::string_view to_string(build_path p) noexcept { return p == build_path::compute ? "compute" : "raster"; }

/// What the current context lacks for build_path::compute, or "" when it has everything: OpenGL 4.3
/// core and nothing more (no extension: every compute program is 32-bit integer and float arithmetic,
/// scripts/validate_shaders.py checks it in SPIR-V). The passes' 8 shader storage blocks, 4 image
/// uniforms and 32 KiB of shared memory are within GL 4.3's minimums; a driver below them fails here
/// rather than at link.
inline std::string compute_path_missing() {
    if (gl_version() < 43) return "OpenGL 4.3 (compute shaders)";
    GLint value = 0;
    glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &value);
    if (value < 32 * 1024) return "32 KiB of compute shared memory (the context has " + std::to_string(value) + " bytes)";
    glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &value);
    if (value < 8) return "8 shader storage blocks in a compute shader";
    glGetIntegerv(GL_MAX_COMPUTE_IMAGE_UNIFORMS, &value);
    if (value < 4) return "4 image uniforms in a compute shader";
    return "";
}

/// Throws feature_error, naming what is missing, unless the context runs build_path::compute; `what`
/// names the caller and `instead` what to do.
inline void require_compute_path(const std::string& what, const std::string& instead = "build on build_path::raster instead") {
    if (const auto missing = compute_path_missing(); !missing.empty()) throw feature_error(what + " needs " + missing + "; " + instead);
}

/// The path a build takes unless told otherwise: compute, which every OpenGL 4.3 context runs (the GL
/// back end's least) and which gives the CPU's maps bit for bit. Nothing falls back to raster
/// silently: where compute cannot run (compute_path_missing), building on it throws feature_error.
constexpr build_path default_build_path() noexcept { return build_path::compute; }

namespace detail {

inline constexpr int compute_tile = 16; // texels per side of a compute tile (HS_TILE)

/// Source pieces every compute program starts with (after compile_stage's version line): the
/// defines, the exact division, the two-word integers, the shared snippet.
inline std::vector<std::string_view> compute_pieces(const std::string& defines) {
    static const std::string common_defines = "#define HS_SUBPIXEL_BITS " + std::to_string(HAIRSHADOW_SUBPIXEL_BITS) + "\n#define HS_ALPHA_MAX " +
                                              std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n";
    return {common_defines, defines, shaders::arithmetic_exact_division, shaders::arithmetic_fixed_point, shaders::compute_common};
}

/// Sums a compute pass keeps per texel in one walk of a tile's segments (HS_SUM_SLOTS), in whole groups
/// of four (the passes store array layers of four): the fewest walks that the context's shared memory
/// allows beside `other_bytes`, at `slot_bytes` a sum for each of a tile's texels, and then the
/// smallest group that needs no more walks, so that no walk holds more memory than it must. 32 KiB,
/// the least compute_path_missing accepts, holds 12 float sums: OSM 64 in 6 walks. Every walk costs
/// a pass over the tile's segments (BENCHMARKS.md); what a larger group costs a GPU in work groups
/// resident at once is not measured.
inline int sums_per_walk(int needed, int slot_bytes, int other_bytes) {
    GLint limit = 0;
    glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &limit);
    const int group_bytes = compute_tile * compute_tile * 4 * slot_bytes;
    const int most = std::max(1, (int(limit) - other_bytes) / group_bytes); // groups of four a walk holds
    const int groups = (std::max(needed, 1) + 3) / 4;
    const int walks = (groups + most - 1) / most;
    return 4 * ((groups + walks - 1) / walks);
}

/// Rows of a compute tile in a strip whose texels each need `texel_bytes` of shared memory: as few
/// strips as the context's shared memory holds, of rows as equal as may be (density clustering's
/// k-means sums and state: a strip walks the tile's segments three times).
inline int strip_rows(int texel_bytes) {
    GLint limit = 0;
    glGetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &limit);
    const int most = std::clamp(int(limit) / (compute_tile * texel_bytes), 1, compute_tile);
    const int strips = (compute_tile + most - 1) / most;
    return (compute_tile + strips - 1) / strips;
}

inline void set_uniform(GLuint prog, const char* name, int v) { glUniform1i(glGetUniformLocation(prog, name), v); }
inline void set_uniform_u(GLuint prog, const char* name, std::uint32_t v) { glUniform1ui(glGetUniformLocation(prog, name), v); }

/// The segments of one mesh seen from one light, prepared and binned on the GPU.
class compute_segments {
    // compute/common's hs_tile_offset_buffer: its words before hs_tile_offsets, and which is which.
    static constexpr std::size_t header_bytes = 32;
    static constexpr std::size_t pairs_word = 2, long_listed_word = 3, long_binned_word = 4, long_wanted_word = 6;

public:
    compute_segments() {
        require_compute_path("the compute build path");
        const auto program_of = [](std::string_view body, const std::string& defines, const std::string& name) {
            auto pieces = compute_pieces(defines);
            pieces.push_back(body);
            const auto s = compile_stage(GL_COMPUTE_SHADER, {}, pieces, name);
            return link_program({&s}, name);
        };
        prepare_ = program_of(shaders::compute_prepare, "", "compute/prepare");
        scan_ = program_of(shaders::compute_scan, "", "compute/scan");
        scatter_ = program_of(shaders::compute_scatter, "", "compute/scatter");
        range_ = program_of(shaders::compute_range, "#define HS_DEPTH_ONLY\n", "compute/range");
        for (auto* b : {&segments_, &counts_, &offsets_, &binned_, &header_copy_}) *b = make_buffer();
    }

    /// Prepares and bins `mesh`'s segments for `light`, writes the range map and the map's extent
    /// into `range` (RGBA32F, res x res + 1), all on the GPU. A run like the last (as many segments, the
    /// same resolution) reads back only the last run's binning counts; any other runs the prepare pass
    /// twice, waiting for the first's count of long segments' tiles. The caller holds a state_guard.
    void run(const hair_mesh& mesh, const light_space& light, const raster_options& options, GLuint range) {
        if (options.wide_line_width > 0.0f)
            throw feature_error("build_path::compute draws thin lines only: wide lines need build_path::raster");
        light_ = light;
        options_ = options;
        one_alpha_ = options.fixed_alpha || (mesh.uniform_attributes() && !footprint_varies());
        const int res = light.resolution();
        tiles_x_ = (res + compute_tile - 1) / compute_tile;
        const std::size_t tiles = std::size_t(tiles_x_) * std::size_t(tiles_x_);
        // The buffers the shaders index: 48 bytes a segment, and their indices in 32 bits.
        GLint64 block = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
        const std::size_t segments = mesh.segment_count();
        if (segments > std::numeric_limits<std::uint32_t>::max() / (short_tiles + 2) || double(segments) * 48.0 > double(block))
            throw feature_error("build_path::compute holds 48 bytes a segment in one shader storage block: " + std::to_string(segments) +
                                " segments need more than this context's " + std::to_string(block) + " bytes; use build_path::raster");
        // The capacity for long segments' pairs: what an earlier run like this one asked for (the same
        // number of segments, the same resolution), otherwise measured first (learn_long_capacity).
        const bool known = built_ && segments == segment_count_ && res == resolution_;
        if (known) learn_long_capacity();
        segment_count_ = segments;
        resolution_ = res;
        built_ = true;
        grow(segments_, segment_bytes_, std::max<std::size_t>(segment_count_, 1) * 48);
        grow(counts_, count_bytes_, tiles * 4);
        grow(offsets_, offset_bytes_, header_bytes + (tiles + 1) * 4);
        grow(header_copy_, header_copy_bytes_, header_bytes);
        const std::size_t most_words = std::min<std::size_t>(std::numeric_limits<std::uint32_t>::max(), std::size_t(block) / 4);
        const auto size_lists = [&] {
            // Short segments in at most 4 tiles' lists each, long ones in the tiles their lines reach while
            // the capacity for them lasts, and a word each for the long list (compute/common's hs_binned).
            const std::size_t words_before = (short_tiles + 1) * std::max<std::size_t>(segment_count_, 1);
            long_capacity_ = std::min(std::max(long_capacity_, segment_count_), most_words - std::min(most_words, words_before));
            grow(binned_, binned_bytes_, (words_before + long_capacity_) * 4, most_words * 4);
        };

        // 1. Prepare and count.
        set_prepare_uniforms(mesh, light);
        if (!known) { // a first pass that lists no long segment in tiles, for what they ask (a wait for the GPU)
            size_lists();
            prepare(0);
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            const std::size_t wanted = read_header()[long_wanted_word];
            long_capacity_ = wanted + wanted / 4;
        }
        size_lists();
        prepare(GLuint(long_capacity_));

        // 2. Offsets and the extent.
        glUseProgram(scan_.get());
        set_light_uniforms(scan_.get());
        set_uniform_u(scan_.get(), "hs_tile_total", GLuint(tiles));
        glBindImageTexture(0, range, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        // 3. Scatter.
        glUseProgram(scatter_.get());
        set_light_uniforms(scatter_.get());
        set_uniform_u(scatter_.get(), "hs_segment_count", GLuint(segment_count_));
        dispatch_segments();
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        // 4. The range map.
        glUseProgram(range_.get());
        set_light_uniforms(range_.get());
        set_shading_uniforms(range_.get());
        glBindImageTexture(0, range, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        dispatch_tiles();

        // 5. This run's counts, copied for the next run to read once the GPU has passed the fence.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, offsets_.get());
        glBindBuffer(GL_ARRAY_BUFFER, header_copy_.get());
        glCopyBufferSubData(GL_SHADER_STORAGE_BUFFER, GL_ARRAY_BUFFER, 0, 0, header_bytes);
        header_fence_.place();
    }

    /// Binds the segment lists (storage bindings 0 to 3) and sets the uniforms every tile pass reads.
    void bind_for_tiles(GLuint prog) const {
        bind_lists();
        set_light_uniforms(prog);
        set_shading_uniforms(prog);
    }
    /// Every segment of the last run has one alpha (a fixed alpha, or uniform attributes and a
    /// footprint that does not vary): its tile passes may take the segment's optical depth for each
    /// fragment (HS_ONE_ALPHA, compute_pass_program).
    bool one_alpha() const noexcept { return one_alpha_; }
    /// One work group per tile.
    void dispatch_tiles() const { glDispatchCompute(GLuint(tiles_x_), GLuint(tiles_x_), 1); }
    /// How the last run binned its segments.
    struct binning {
        std::size_t pairs = 0;        ///< segment-tile pairs in the tiles' lists
        std::size_t long_listed = 0;  ///< long segments in the long list, read through by every tile
        std::size_t long_binned = 0;  ///< long segments in the lists of the tiles their lines reach
        std::size_t long_pairs = 0;   ///< the pairs the long segments asked for (modulo 2^32)
        std::size_t long_capacity = 0; ///< the words the run set aside for them
    };
    /// The last run's binning, read back (a wait for the GPU), for tests and inspection.
    binning counts() const {
        state_guard guard("hairshadow: compute pair counts"); // the caller's storage buffer binding stays
        if (!built_) return {};
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const auto words = read_header();
        return {words[pairs_word], words[long_listed_word], words[long_binned_word], words[long_wanted_word], long_capacity_};
    }

private:
    /// Clears the counts and the header, and runs the prepare pass with `long_capacity` words for
    /// long segments' pairs.
    void prepare(GLuint long_capacity) const {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // the clears below wait for the last run's shaders
        const GLuint zero = 0;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, counts_.get());
        glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        std::uint32_t header[header_bytes / 4] = {}; // compute/common's hs_tile_offset_buffer, before the offsets
        header[0] = 0xffffffffu;                     // the nearest depth's ordered bits: none yet
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, offsets_.get());
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof header, header);
        bind_lists();
        const GLuint p = prepare_.get();
        glUseProgram(p);
        set_light_uniforms(p);
        set_uniform_u(p, "hs_long_capacity", long_capacity);
        dispatch_segments();
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    /// The prepare pass's uniforms and bindings that stay for a run: the mesh's buffers and the light.
    void set_prepare_uniforms(const hair_mesh& mesh, const light_space& light) const {
        const auto& src = mesh.sources();
        const GLuint p = prepare_.get();
        glUseProgram(p);
        const auto layout = [&](const char* name, const buffer_attribute& a, std::size_t floats) {
            const std::size_t stride = a.stride == 0 ? floats : std::size_t(a.stride) / 4;
            glUniform2ui(glGetUniformLocation(p, name), GLuint(std::size_t(a.offset) / 4), GLuint(stride));
        };
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, src.points.positions.buffer);
        layout("hs_position_layout", src.points.positions, 3);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, src.points.thickness ? src.points.thickness->buffer : src.points.positions.buffer);
        if (src.points.thickness) layout("hs_thickness_layout", *src.points.thickness, 1);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, src.points.opacity ? src.points.opacity->buffer : src.points.positions.buffer);
        if (src.points.opacity) layout("hs_opacity_layout", *src.points.opacity, 1);
        set_uniform(p, "hs_thickness_constant", src.points.thickness ? 0 : 1);
        set_uniform(p, "hs_opacity_constant", src.points.opacity ? 0 : 1);
        glUniform1f(glGetUniformLocation(p, "hs_thickness_value"), src.points.uniform_thickness);
        glUniform1f(glGetUniformLocation(p, "hs_opacity_value"), src.points.uniform_opacity);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, src.index_buffer);
        set_uniform_u(p, "hs_index_first", GLuint(std::size_t(src.index_offset) / 4));
        set_uniform_u(p, "hs_segment_count", GLuint(segment_count_));
        set_uniform(p, "hs_tile_size", compute_tile);
        glUniformMatrix4fv(glGetUniformLocation(p, "hs_view_projection"), 1, GL_FALSE, &light.view_projection()[0][0]);
        glUniformMatrix4fv(glGetUniformLocation(p, "hs_view"), 1, GL_FALSE, &light.view()[0][0]);
        glUniform1f(glGetUniformLocation(p, "hs_near"), light.near_plane());
        glUniform1f(glGetUniformLocation(p, "hs_far"), light.far_plane());
    }
    /// compute/common's hs_tile_offset_buffer header of the last run (a wait for the GPU).
    std::array<std::uint32_t, header_bytes / 4> read_header() const {
        std::array<std::uint32_t, header_bytes / 4> words{};
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, offsets_.get());
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof words, words.data());
        return words;
    }
    /// The capacity for long segments' pairs in a run like the last (the same segment count and
    /// resolution): what the last run's long segments asked for, and a quarter more for a moving mesh,
    /// read from the copy run() made, once the GPU has passed it; until then, the last capacity (no
    /// wait). A run whose long segments ask for more lists those past it in the long list: the same
    /// maps, slower passes.
    void learn_long_capacity() {
        if (!header_fence_.passed()) return;
        header_fence_.reset();
        std::array<std::uint32_t, header_bytes / 4> words{};
        glBindBuffer(GL_ARRAY_BUFFER, header_copy_.get());
        glGetBufferSubData(GL_ARRAY_BUFFER, 0, header_bytes, words.data());
        const std::size_t wanted = words[long_wanted_word];
        if (words[long_listed_word] != 0) long_capacity_ = std::max(long_capacity_ * 2, wanted + wanted / 4); // wanted may have wrapped
        else long_capacity_ = std::max(long_capacity_, wanted + wanted / 4);
    }
    /// Grows `b` to `needed` bytes and a quarter more, within `most` (where the shaders index it).
    static void grow(buffer& b, std::size_t& bytes, std::size_t needed, std::size_t most = std::numeric_limits<std::size_t>::max()) {
        if (needed <= bytes) return;
        bytes = std::max(needed, std::min(bytes + bytes / 4, most));
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, b.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_COPY);
    }
    void bind_lists() const {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, segments_.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counts_.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, offsets_.get());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, binned_.get());
    }
    void set_light_uniforms(GLuint prog) const {
        set_uniform(prog, "hs_resolution", light_.resolution());
        set_uniform(prog, "hs_tiles_x", tiles_x_);
        set_uniform_u(prog, "hs_long_first", GLuint(short_tiles * segment_count_ + long_capacity_));
    }
    /// A fragment's footprint, and so its alpha, changes with its depth (segment_shader's depth weighting).
    bool footprint_varies() const noexcept { return light_.perspective() && options_.depth_weighting; }
    void set_shading_uniforms(GLuint prog) const {
        set_uniform(prog, "hs_use_fixed_alpha", options_.fixed_alpha ? 1 : 0);
        glUniform1f(glGetUniformLocation(prog, "hs_fixed_alpha"), options_.fixed_alpha.value_or(0.0f));
        glUniform1f(glGetUniformLocation(prog, "hs_footprint"), light_.texel_size(0.5f));
        set_uniform(prog, "hs_footprint_varies", footprint_varies() ? 1 : 0);
        glUniform4f(glGetUniformLocation(prog, "hs_footprint_terms"), 2.0f * light_.half_extent(), light_.near_plane(),
                    light_.far_plane() - light_.near_plane(), float(light_.resolution()));
    }
    /// One invocation per segment: groups of 256 in rows of at most 65535 groups.
    void dispatch_segments() const {
        const std::size_t groups = (segment_count_ + 255) / 256;
        if (groups == 0) return;
        const std::size_t x = std::min<std::size_t>(groups, 65535), y = (groups + x - 1) / x;
        glDispatchCompute(GLuint(x), GLuint(y), 1);
    }

    program prepare_, scan_, scatter_, range_;
    buffer segments_, counts_, offsets_, binned_, header_copy_;
    fence_sync header_fence_;
    std::size_t segment_bytes_ = 0, count_bytes_ = 0, offset_bytes_ = 0, binned_bytes_ = 0, header_copy_bytes_ = 0;
    static constexpr std::size_t short_tiles = 4;  // HS_SHORT_TILES
    std::size_t segment_count_ = 0, long_capacity_ = 0;
    bool one_alpha_ = false;
    int resolution_ = 0;
    bool built_ = false;
    int tiles_x_ = 0;
    light_space light_;
    raster_options options_;
};

/// A tile pass's program in two forms, each linked on first use: one for runs whose segments each
/// have one alpha (HS_ONE_ALPHA: hs_shade takes the segment's optical depth, never works one out per
/// fragment) and one for the rest. One program would do for both, but llvmpipe runs both sides of
/// every branch under lane masks, and the per-fragment path cost about a quarter of dom:3's pass on
/// Sintel where no segment took it (BENCHMARKS.md, "where llvmpipe's compute time goes").
class compute_pass_program {
public:
    /// The form for `segments`' last run; `link(defines)` links a program with `defines` added.
    template <class Link>
    GLuint for_run(const compute_segments& segments, Link&& link) {
        program& p = programs_[segments.one_alpha() ? 1 : 0];
        if (!p) p = link(std::string(segments.one_alpha() ? "#define HS_ONE_ALPHA\n" : ""));
        return p.get();
    }

private:
    std::array<program, 2> programs_;
};

} // namespace detail
} // namespace hairshadow::gl
