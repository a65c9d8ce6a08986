#pragma once
/// @file
/// Transparent hair on GL (Sintorn & Assarsson 2009, section 3.4). The hair's fragments are seen
/// from the camera as hairshadow::collect_camera_fragments makes them (transparency/camera_fragment)
/// and blended over an opaque image by each mode of hairshadow::transparency:
/// - occupancy-ordered blending, from occupancy and slab maps of the camera's fragments built by
///   the shadow maps' own passes (128 slices, 4 slabs, as on the CPU);
/// - weighted averages (Bavoil & Myers 2008);
/// - exact blending, by depth peeling.

#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/context/state_guard.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/shading/camera.hpp>
#include <hairshadow/shading/transparency.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace hairshadow::gl {

/// What the blend draws and draws over, all at the camera's image size.
struct camera_hair {
    std::function<void()> draw_lines; ///< draws every hair segment (GL_LINES, positions at attribute 0, indices = point indices)
    GLuint colours = 0;               ///< shader storage buffer: light k's radiance of point i at vec4 k * point_count + i
    int light_count = 0, point_count = 0;
    glm::vec3 ambient{0.0f};          ///< added to every point's colour
    GLuint surface_inv_w = 0;         ///< R32F texture: the mesh's 1/w at each pixel (0 where there is none)
    GLuint base = 0;                  ///< RGBA32F texture: the mesh and background, linear
};

/// The passes of every transparency mode, compiled at their first use.
class transparent_hair {
public:
    transparent_hair() { check_support(); }

    /// Throws feature_error unless the current context can draw transparent hair: GL 4.3, and shader
    /// storage in vertex shaders (which GL 4.3 allows an implementation to lack).
    static void check_support() {
        require_version(4, 3, "transparent hair");
        GLint blocks = 0;
        glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &blocks);
        if (blocks < 1) throw feature_error("transparent hair needs shader storage blocks in vertex shaders; the context has none");
    }

    /// Depth peeling stops with an error beyond this many layers (it ends by itself: each layer is
    /// strictly deeper than the last, in every pixel).
    static constexpr int max_layers = 1 << 16;

    /// Blends `hair` over its base image by `mode` (not transparency::none) into colour attachment 0
    /// of framebuffer `target` (linear RGB), each strand of `opacity` and `line_width` pixels.
    /// Returns the number of depth-peeling layers (transparency::exact; one draw of the hair each,
    /// and two more), else 0.
    int blend(transparency mode, const camera_hair& hair, const camera& cam, float opacity, float line_width, GLuint target) {
        const caller_errors_kept kept; // the caller's unread errors stay theirs, and fail nothing here
        if (mode == transparency::none) throw argument_error("transparent_hair::blend needs a transparency mode");
        if (!(opacity > 0.0f && opacity <= 1.0f)) throw argument_error("hair opacity must be in (0, 1]");
        if (!(line_width > 0.0f && line_width <= 64.0f)) throw argument_error("hair line width must be in (0, 64] pixels");
        if (!hair.draw_lines || !hair.colours || !hair.surface_inv_w || !hair.base || hair.light_count < 0 || hair.point_count < 0)
            throw argument_error("transparent_hair::blend needs the hair's lines, colours, the surface's 1/w and the base image");
        camera::check_image_size(cam.width, cam.height);
        GLint max_size = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
        if (cam.width > max_size || cam.height > max_size)
            throw feature_error("transparent hair at " + std::to_string(cam.width) + "x" + std::to_string(cam.height) + " needs textures that large; the context allows " +
                                std::to_string(max_size));
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_SCISSOR_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glViewport(0, 0, cam.width, cam.height);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, hair.colours);
        const frame f{hair, cam, opacity, line_width};
        int layers = 0;
        texture sum, total;
        switch (mode) {
        case transparency::occupancy: std::tie(sum, total) = occupancy_order(f); break;
        case transparency::weighted: std::tie(sum, total) = weighted_sums(f); break;
        default: std::tie(sum, layers) = peel(f); break;
        }
        resolve(mode, f, sum, total.get() ? total : sum, target);
        check("transparent hair");
        return layers;
    }

private:
    /// The occupancy maps of the camera's fragments: Sintorn & Assarsson's 128 slices in 4 slabs.
    static constexpr int slices = 128, slabs = 4;

    struct frame {
        const camera_hair& hair;
        const camera& cam;
        float opacity, line_width;
    };

    static std::string defines() {
        return "#define HS_ALPHA_MAX " + std::to_string(HAIRSHADOW_ALPHA_MAX) + "\n#define HS_LAYERS " + std::to_string(slices) +
               "\n#define HS_SLABS " + std::to_string(slabs) + "\n#define HS_BIT_TARGETS 1\n#define HS_SLAB_TARGETS 1\n";
    }

    /// A program drawing the camera's fragments, its fragment stage composed of `pieces` after the
    /// occupancy maps' snippets and transparency/camera_fragment.
    static program line_program(std::initializer_list<std::string_view> pieces, const std::string& name) {
        const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::transparency_line_vertex}, "transparency/line_vertex");
        const auto gs = compile_stage(GL_GEOMETRY_SHADER, {}, {shaders::transparency_line_geometry}, "transparency/line_geometry");
        std::vector<std::string_view> fragment{shaders::accumulation_float, shaders::arithmetic_exact_division, shaders::placement_common, shaders::placement_depth_range,
                                               shaders::texel_state_depth_range, shaders::transparency_camera_fragment};
        fragment.insert(fragment.end(), pieces);
        const auto fs = compile_stage(GL_FRAGMENT_SHADER, defines(), fragment, name);
        return link_program({&vs, &gs, &fs}, name);
    }

    /// The program for `key`, compiled the first time it is asked for.
    const program& cached(const std::string& key, const std::function<program()>& make) {
        auto found = programs_.find(key);
        if (found == programs_.end()) found = programs_.emplace(key, make()).first;
        return found->second;
    }

    static texture target_texture(GLenum format, const camera& cam) { return make_texture_2d(format, cam.width, cam.height); }

    /// Binds a framebuffer drawing into `textures` (colour attachments 0, 1, ...).
    static framebuffer draw_into(std::initializer_list<GLuint> textures) {
        auto fbo = make_framebuffer();
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        std::vector<GLenum> buffers;
        for (GLuint t : textures) {
            const auto attachment = GLenum(GL_COLOR_ATTACHMENT0 + buffers.size());
            glFramebufferTexture(GL_FRAMEBUFFER, attachment, t, 0);
            buffers.push_back(attachment);
        }
        glDrawBuffers(GLsizei(buffers.size()), buffers.data());
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) throw gl_error("transparent hair: incomplete framebuffer");
        return fbo;
    }

    static void bind_texture(GLuint prog, const char* name, int unit, GLuint t) {
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        glBindTexture(GL_TEXTURE_2D, t);
        glUniform1i(glGetUniformLocation(prog, name), unit);
        glActiveTexture(GL_TEXTURE0);
    }

    /// Draws the camera's fragments with `p` (blending is the caller's); units 0-2 are the pass's own.
    static void draw_fragments(const program& p, const frame& f) {
        const GLuint prog = p.get();
        glUseProgram(prog);
        const auto vp = f.cam.view_projection();
        glUniformMatrix4fv(glGetUniformLocation(prog, "hs_camera_view_projection"), 1, GL_FALSE, &vp[0][0]);
        glUniform2f(glGetUniformLocation(prog, "hs_viewport"), float(f.cam.width), float(f.cam.height));
        glUniform1f(glGetUniformLocation(prog, "hs_line_reach"), 0.5f * f.line_width + 0.5f);
        glUniform1f(glGetUniformLocation(prog, "hs_hair_opacity"), f.opacity);
        glUniform1f(glGetUniformLocation(prog, "hs_camera_near"), f.cam.near_plane);
        glUniform1f(glGetUniformLocation(prog, "hs_camera_far"), f.cam.far_plane);
        glUniform3fv(glGetUniformLocation(prog, "hs_hair_ambient_colour"), 1, &f.hair.ambient[0]);
        glUniform1i(glGetUniformLocation(prog, "hs_light_count"), f.hair.light_count);
        glUniform1i(glGetUniformLocation(prog, "hs_point_count"), f.hair.point_count);
        bind_texture(prog, "hs_surface_inv_w", 3, f.hair.surface_inv_w);
        f.hair.draw_lines();
    }

    static void clear(int draw_buffer, float r, float g, float b, float a) {
        const float value[4] = {r, g, b, a};
        glClearBufferfv(GL_COLOR, draw_buffer, value);
    }

    static void additive() {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
    }

    /// Occupancy-ordered blending: the camera's depth range, occupancy and slab maps, then one
    /// unsorted pass of (1 - alpha)^o alpha (colour, 1) and the sum of -ln(1 - alpha).
    std::pair<texture, texture> occupancy_order(const frame& f) {
        // Compiled before any state changes, so that a compile error leaves the context as it was.
        const auto& range_pass = cached("range", [] { return line_program({shaders::passes_depth_range}, "transparency: depth range"); });
        const auto& bits_pass = cached("bits", [] { return line_program({shaders::passes_occupancy_bits}, "transparency: occupancy bits"); });
        const auto& slabs_pass = cached("slabs", [] { return line_program({shaders::passes_occupancy_slabs}, "transparency: slabs"); });
        const auto& order_pass = cached("order", [] {
            return line_program({shaders::reconstruction_occupancy_bitcount, shaders::lookup_occupancy_texels, shaders::transparency_occupancy_order},
                                "transparency: occupancy order");
        });
        auto range = target_texture(GL_RGBA32F, f.cam), bits = target_texture(GL_RGBA32UI, f.cam), slab = target_texture(GL_RGBA32F, f.cam);
        // 1. Each pixel's nearest and furthest fragment (Sintorn & Assarsson 3.1).
        {
            const auto fbo = draw_into({range.get()});
            clear(0, 3.0e38f, 0.0f, 0.0f, -3.0e38f);
            glEnable(GL_BLEND);
            glBlendEquationSeparate(GL_MIN, GL_MAX);
            glBlendFunc(GL_ONE, GL_ONE);
            draw_fragments(range_pass, f);
            glBlendEquation(GL_FUNC_ADD);
            glDisable(GL_BLEND);
        }
        // 2. The occupancy bits (OR) and 3. the slabs' optical depths (additive), as for a light.
        {
            const auto fbo = draw_into({bits.get()});
            const GLuint zero[4] = {0, 0, 0, 0};
            glClearBufferuiv(GL_COLOR, 0, zero);
            glEnable(GL_COLOR_LOGIC_OP);
            glLogicOp(GL_OR);
            glUseProgram(bits_pass.get());
            bind_texture(bits_pass.get(), "hs_range_map", 0, range.get());
            draw_fragments(bits_pass, f);
            glDisable(GL_COLOR_LOGIC_OP);
        }
        {
            const auto fbo = draw_into({slab.get()});
            clear(0, 0.0f, 0.0f, 0.0f, 0.0f);
            additive();
            glUseProgram(slabs_pass.get());
            bind_texture(slabs_pass.get(), "hs_range_map", 0, range.get());
            draw_fragments(slabs_pass, f);
            glDisable(GL_BLEND);
        }
        // 4. The blend pass, in drawing order: each fragment's weight from its slice's depth order.
        auto sum = target_texture(GL_RGBA32F, f.cam), total = target_texture(GL_R32F, f.cam);
        const auto fbo = draw_into({sum.get(), total.get()});
        clear(0, 0.0f, 0.0f, 0.0f, 0.0f);
        clear(1, 0.0f, 0.0f, 0.0f, 0.0f);
        additive();
        glUseProgram(order_pass.get());
        bind_texture(order_pass.get(), "hs_range_map", 0, range.get());
        bind_texture(order_pass.get(), "hs_bits_texture[0]", 1, bits.get());
        bind_texture(order_pass.get(), "hs_slabs_texture[0]", 2, slab.get());
        draw_fragments(order_pass, f);
        glDisable(GL_BLEND);
        return {std::move(sum), std::move(total)};
    }

    /// Weighted averages: one unsorted additive pass of (alpha colour, alpha) and the fragment count.
    std::pair<texture, texture> weighted_sums(const frame& f) {
        const auto& p = cached("weighted", [] { return line_program({shaders::transparency_weighted_sum}, "transparency: weighted sums"); });
        auto sum = target_texture(GL_RGBA32F, f.cam), count = target_texture(GL_R32F, f.cam);
        const auto fbo = draw_into({sum.get(), count.get()});
        clear(0, 0.0f, 0.0f, 0.0f, 0.0f);
        clear(1, 0.0f, 0.0f, 0.0f, 0.0f);
        additive();
        draw_fragments(p, f);
        glDisable(GL_BLEND);
        return {std::move(sum), std::move(count)};
    }

    /// Exact blending by depth peeling, front to back: a first draw finds each pixel's nearest
    /// depth, then each draw blends one layer and finds the next (transparency/peel), until an
    /// occlusion query sees no fragment left. Returns the under-blended colour and transmittance,
    /// and the number of layers (the draws less two: the first finds, the last finds nothing).
    std::pair<texture, int> peel(const frame& f) {
        const auto& p = cached("peel", [] { return line_program({shaders::transparency_peel}, "transparency: depth peeling"); });
        auto accumulated = target_texture(GL_RGBA32F, f.cam);
        std::array<texture, 2> layer{target_texture(GL_RGBA32F, f.cam), target_texture(GL_RGBA32F, f.cam)};
        // Draw k reads layer[k % 2] and finds the next layer into layer[(k + 1) % 2].
        std::array<framebuffer, 2> fbo{draw_into({accumulated.get(), layer[1].get()}), draw_into({accumulated.get(), layer[0].get()})};
        clear(0, 0.0f, 0.0f, 0.0f, 1.0f);
        GLuint query_name = 0;
        glGenQueries(1, &query_name);
        const query any_left(query_name);
        glUseProgram(p.get());
        glEnablei(GL_BLEND, 0);
        glEnablei(GL_BLEND, 1);
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFuncSeparatei(0, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        glBlendEquationSeparatei(1, GL_MIN, GL_MAX);
        int draws = 0;
        for (;; ++draws) {
            if (draws == max_layers + 2) {
                reset_blending();
                throw gl_error("depth peeling found more than " + std::to_string(max_layers) + " layers");
            }
            const std::size_t current = std::size_t(draws % 2);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo[current].get());
            // Infinity, so that fragments at infinite depth (1/w = 0) are found, blended and passed.
            clear(1, std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f);
            glUniform1i(glGetUniformLocation(p.get(), "hs_first_layer"), draws == 0);
            bind_texture(p.get(), "hs_layer_depth", 0, layer[current].get());
            glBeginQuery(GL_ANY_SAMPLES_PASSED, any_left.get());
            draw_fragments(p, f);
            glEndQuery(GL_ANY_SAMPLES_PASSED);
            GLuint left = 0;
            glGetQueryObjectuiv(any_left.get(), GL_QUERY_RESULT, &left);
            if (!left) break;
        }
        reset_blending();
        return {std::move(accumulated), std::max(0, draws - 1)};
    }

    /// GL's default blending, for every draw buffer.
    static void reset_blending() {
        glDisable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ZERO);
    }

    void resolve(transparency mode, const frame& f, const texture& sum, const texture& total, GLuint target) {
        const char* define = mode == transparency::occupancy ? "#define HS_OCCUPANCY_ORDER\n"
                             : mode == transparency::weighted ? "#define HS_WEIGHTED_AVERAGE\n"
                                                              : "#define HS_EXACT\n";
        const auto& p = cached(std::string("resolve ") + define, [define] {
            const auto vs = compile_stage(GL_VERTEX_SHADER, {}, {shaders::passes_fullscreen_vertex}, "passes/fullscreen_vertex");
            const auto fs = compile_stage(GL_FRAGMENT_SHADER, {}, {define, shaders::transparency_resolve}, "transparency/resolve");
            return link_program({&vs, &fs}, "transparency: resolve");
        });
        glBindFramebuffer(GL_FRAMEBUFFER, target);
        glDisable(GL_BLEND);
        glUseProgram(p.get());
        bind_texture(p.get(), "hs_base", 0, f.hair.base);
        bind_texture(p.get(), "hs_sum", 1, sum.get());
        bind_texture(p.get(), "hs_total", 2, total.get());
        glBindVertexArray(empty_vao_.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
    }

    std::map<std::string, program> programs_;
    vertex_array empty_vao_ = make_vertex_array();
};

} // namespace hairshadow::gl
