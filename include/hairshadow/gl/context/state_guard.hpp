#pragma once
/// @file
/// The GL back end's state contract (README, "The GL state contract"): every entry point that draws,
/// dispatches or reads back saves the GL state it may change and restores it on the way out, sets the
/// state its passes depend on whatever the caller left, and lets the caller's unread GL errors
/// neither fail it nor be mistaken for its own, leaving them for the caller to read after the call.
/// One path for every GL 4.3+ context.

#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/context/error.hpp>

#include <algorithm>
#include <array>
#include <string>

namespace hairshadow::gl {

namespace detail {
/// True where the loader gave `f` (a prototype, or a loader's function pointer).
template <class F>
bool loaded(F* f) noexcept {
    return f != nullptr;
}

/// The GL errors a caller left unread when a library call began: read first, since reading them is
/// the only way to tell the library's own apart, and raised again when the call ends, so that the
/// caller's glGetError still finds them (GL keeps one flag per kind, so the set is small).
class pending_errors {
public:
    /// Reads every error flag GL has set. GL_OUT_OF_MEMORY leaves GL's state undefined (GL 4.6, 2.3.1):
    /// the library does not build on it, and says so.
    void take() {
        bool out_of_memory = false;
        for (int read = 0; read < 16; ++read) { // bounded: a driver without a current context may repeat one error
            const GLenum e = glGetError();
            if (e == GL_NO_ERROR) break;
            if (e == GL_OUT_OF_MEMORY) out_of_memory = true;
            else if (count_ < errors_.size() && std::find(errors_.begin(), errors_.begin() + count_, e) == errors_.begin() + count_) errors_[count_++] = e;
        }
        if (out_of_memory) {
            raise_again(); // the others stay the caller's; GL_OUT_OF_MEMORY itself cannot be raised again
            count_ = 0;
            throw gl_error("GL_OUT_OF_MEMORY was pending before hairshadow's call (read, and so cleared): the GL state is undefined (GL 4.6, section 2.3.1)");
        }
    }

    /// Sets each flag again by a call that GL rejects with that error and otherwise ignores (GL 4.6,
    /// 2.3.1: a command that raises an error has no other effect), with debug output off meanwhile so
    /// that the caller's debug callback does not hear its errors twice. GL_STACK_UNDERFLOW is raised
    /// only where the debug group stack holds the default group alone, GL_STACK_OVERFLOW only where
    /// it is full (elsewhere raising them would pop or push a group of the caller's); GL_CONTEXT_LOST
    /// cannot be raised.
    void raise_again() const noexcept {
        if (count_ == 0) return;
        const GLboolean debug_output = glIsEnabled(GL_DEBUG_OUTPUT);
        glDisable(GL_DEBUG_OUTPUT);
        for (std::size_t i = 0; i < count_; ++i) raise(errors_[i]);
        if (debug_output) glEnable(GL_DEBUG_OUTPUT);
    }

private:
    static void raise(GLenum e) noexcept {
        switch (e) {
        case GL_INVALID_ENUM: glEnable(GL_NONE); break;       // not a capability
        case GL_INVALID_VALUE: glLineWidth(-1.0f); break;     // width <= 0
        case GL_INVALID_OPERATION: glBeginQuery(GL_SAMPLES_PASSED, 0); break; // query name 0
        case GL_INVALID_FRAMEBUFFER_OPERATION: raise_framebuffer_error(); break;
        case GL_STACK_UNDERFLOW: if (debug_group_depth() <= 1) glPopDebugGroup(); break; // the default group counts
        case GL_STACK_OVERFLOW: raise_stack_overflow(); break;
        default: break;
        }
    }
    static GLint debug_group_depth() noexcept {
        GLint depth = 0;
        glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depth);
        return depth;
    }
    static void raise_stack_overflow() noexcept {
        GLint max_depth = 0;
        glGetIntegerv(GL_MAX_DEBUG_GROUP_STACK_DEPTH, &max_depth);
        if (debug_group_depth() >= max_depth) glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "hairshadow");
    }
    /// A clear of a framebuffer with no attachment and no default size, which is incomplete.
    static void raise_framebuffer_error() noexcept {
        GLint bound = 0;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
        GLuint fbo = 0;
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        glClear(GL_COLOR_BUFFER_BIT);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(bound));
        glDeleteFramebuffers(1, &fbo);
    }

    std::array<GLenum, 8> errors_{};
    std::size_t count_ = 0;
};
} // namespace detail

/// Keeps the caller's unread GL errors apart for a scope: read when made, raised again when
/// destroyed, so that a check() inside reports only the library's own. Nested keepers hold nothing
/// (the outer one took them). The state guard holds one; the renderer's entry points, which change
/// state by design, hold one of their own.
class caller_errors_kept {
public:
    caller_errors_kept() { errors_.take(); }
    ~caller_errors_kept() { errors_.raise_again(); }
    caller_errors_kept(const caller_errors_kept&) = delete;
    caller_errors_kept& operator=(const caller_errors_kept&) = delete;

private:
    detail::pending_errors errors_;
};

/// Saves, when made, the GL state the library's passes and read-backs may change, and restores it
/// when destroyed (also when a pass throws):
/// - bindings: program, draw and read framebuffers, vertex array, array buffer, the shader storage
///   buffer (generic, and indexed bindings 0 to 7), pixel pack buffer, image units 0 to 3, the active texture
///   unit, and the 2D and 2D-array textures and sampler objects of units [0, saved_units);
/// - fixed-function state: every viewport, scissor tests, colour masks, blending (enables, equations,
///   functions) of every draw buffer, depth and stencil tests, culling, logic op, rasteriser discard,
///   dithering, depth clamp, line smoothing, primitive restart, clip distances, polygon mode, line
///   width, clip control (GL 4.5) and the pixel pack parameters.
/// Transform feedback and conditional rendering must not be active during a build. The saving costs
/// about 150 glGet calls; on a driver that runs GL on a thread of its own (NVIDIA's threaded
/// optimisation), each waits for that thread to catch up.
class state_guard {
public:
    /// Texture units [0, saved_units) hold what the library's passes bind (up to 3) and what point
    /// queries bind for a look-up (up to 1 + 2 + 2 for 256 slices and 8 slabs).
    static constexpr int saved_units = 8;
    /// Asks a guard to save every texture unit the context has (GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS,
    /// at most max_saved_units): for calls that bind a caller's choice of units (point queries).
    static constexpr int all_texture_units = -1, max_saved_units = 256;
    /// Indexed shader storage bindings and image units the passes use (the compute build's), restored.
    static constexpr GLuint saved_storage_bindings = 8, saved_images = 4;

    /// Throws feature_error in a context older than GL 4.3, whose loader may lack the functions used
    /// here, and gl_error where the caller left GL_OUT_OF_MEMORY pending. Saves texture units
    /// [0, texture_units), at least saved_units (all_texture_units: every one).
    explicit state_guard(const char* label, int texture_units = saved_units) {
        if (gl_version() < 43) require_version(4, 3, std::string("the GL back end (") + label + ")"); // the message only on failure
        push_debug_group(label);
        if (texture_units == all_texture_units) glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &texture_units);
        unit_count_ = std::clamp(texture_units, saved_units, max_saved_units);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
        glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_buffer_);
        for (GLuint i = 0; i < saved_storage_bindings; ++i) {
            auto& b = storage_[i];
            glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &b.name);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &b.start);
            glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &b.size);
        }
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
        for (GLuint i = 0; i < saved_images; ++i) {
            auto& image = images_[i];
            glGetIntegeri_v(GL_IMAGE_BINDING_NAME, i, &image.name);
            glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, i, &image.level);
            glGetBooleani_v(GL_IMAGE_BINDING_LAYERED, i, &image.layered);
            glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, i, &image.layer);
            glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, i, &image.access);
            glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, i, &image.format);
        }
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
        for (int u = 0; u < unit_count_; ++u) {
            glActiveTexture(GLenum(GL_TEXTURE0 + u));
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &units_[std::size_t(u)].texture_2d);
            glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &units_[std::size_t(u)].texture_array);
            glGetIntegerv(GL_SAMPLER_BINDING, &units_[std::size_t(u)].sampler);
        }
        glActiveTexture(GLenum(active_texture_));

        GLint count = 0;
        glGetIntegerv(GL_MAX_VIEWPORTS, &count);
        viewports_ = std::min(count, int(max_viewports));
        for (int i = 0; i < viewports_; ++i) {
            glGetFloati_v(GL_VIEWPORT, GLuint(i), viewport_[std::size_t(i)].data());
            scissor_test_[std::size_t(i)] = glIsEnabledi(GL_SCISSOR_TEST, GLuint(i));
        }
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &count);
        draw_buffers_ = std::min(count, int(max_draw_buffers));
        for (int i = 0; i < draw_buffers_; ++i) {
            auto& b = blend_[std::size_t(i)];
            const auto index = GLuint(i);
            b.enabled = glIsEnabledi(GL_BLEND, index);
            glGetBooleani_v(GL_COLOR_WRITEMASK, index, b.mask.data());
            glGetIntegeri_v(GL_BLEND_EQUATION_RGB, index, &b.equation_rgb);
            glGetIntegeri_v(GL_BLEND_EQUATION_ALPHA, index, &b.equation_alpha);
            glGetIntegeri_v(GL_BLEND_SRC_RGB, index, &b.src_rgb);
            glGetIntegeri_v(GL_BLEND_DST_RGB, index, &b.dst_rgb);
            glGetIntegeri_v(GL_BLEND_SRC_ALPHA, index, &b.src_alpha);
            glGetIntegeri_v(GL_BLEND_DST_ALPHA, index, &b.dst_alpha);
        }
        for (std::size_t i = 0; i < capabilities.size(); ++i) enabled_[i] = glIsEnabled(capabilities[i]);
        glGetIntegerv(GL_LOGIC_OP_MODE, &logic_op_);
        glGetIntegerv(GL_POLYGON_MODE, polygon_mode_.data());
        glGetFloatv(GL_LINE_WIDTH, &line_width_);
        for (std::size_t i = 0; i < pack_parameters.size(); ++i) glGetIntegerv(pack_parameters[i], &pack_[i]);
#ifdef GL_CLIP_ORIGIN
        has_clip_control_ = gl_version() >= 45 && detail::loaded(glClipControl);
        if (has_clip_control_) glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_), glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_);
#endif
    }

    state_guard(const state_guard&) = delete;
    state_guard& operator=(const state_guard&) = delete;

    /// Restores what was saved. A name deleted meanwhile (the caller's program deleted while current,
    /// the maps' own textures replaced by a build at a new resolution) restores as 0, as GL itself
    /// unbinds a deleted name: binding it again would be an error.
    ~state_guard() {
        const auto live = [](GLint name, auto is) { return name != 0 && is(GLuint(name)) ? GLuint(name) : 0u; };
        glUseProgram(live(program_, glIsProgram));
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, live(draw_fbo_, glIsFramebuffer));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, live(read_fbo_, glIsFramebuffer));
        glBindVertexArray(live(vao_, glIsVertexArray));
        glBindBuffer(GL_ARRAY_BUFFER, live(array_buffer_, glIsBuffer));
        for (GLuint i = 0; i < saved_storage_bindings; ++i) {
            const auto& b = storage_[i];
            const GLuint storage = live(b.name, glIsBuffer);
            if (storage && b.size > 0) glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, storage, GLintptr(b.start), GLsizeiptr(b.size));
            else glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, storage);
        }
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, live(storage_buffer_, glIsBuffer)); // after the indexed binding, which sets it too
        glBindBuffer(GL_PIXEL_PACK_BUFFER, live(pack_buffer_, glIsBuffer));
        for (GLuint i = 0; i < saved_images; ++i) {
            const auto& b = images_[i];
            const GLuint image = live(b.name, glIsTexture);
            glBindImageTexture(i, image, image ? b.level : 0, image ? b.layered : GL_FALSE, image ? b.layer : 0,
                               image ? GLenum(b.access) : GL_READ_ONLY, image ? GLenum(b.format) : GL_R8);
        }
        for (int u = 0; u < unit_count_; ++u) {
            const auto& unit = units_[std::size_t(u)];
            glActiveTexture(GLenum(GL_TEXTURE0 + u));
            glBindTexture(GL_TEXTURE_2D, live(unit.texture_2d, glIsTexture));
            glBindTexture(GL_TEXTURE_2D_ARRAY, live(unit.texture_array, glIsTexture));
            glBindSampler(GLuint(u), live(unit.sampler, glIsSampler));
        }
        glActiveTexture(GLenum(active_texture_));
        for (int i = 0; i < viewports_; ++i) {
            glViewportIndexedfv(GLuint(i), viewport_[std::size_t(i)].data());
            set_enabled(GL_SCISSOR_TEST, GLuint(i), scissor_test_[std::size_t(i)]);
        }
        for (int i = 0; i < draw_buffers_; ++i) {
            const auto& b = blend_[std::size_t(i)];
            const auto index = GLuint(i);
            set_enabled(GL_BLEND, index, b.enabled);
            glColorMaski(index, b.mask[0], b.mask[1], b.mask[2], b.mask[3]);
            glBlendEquationSeparatei(index, GLenum(b.equation_rgb), GLenum(b.equation_alpha));
            glBlendFuncSeparatei(index, GLenum(b.src_rgb), GLenum(b.dst_rgb), GLenum(b.src_alpha), GLenum(b.dst_alpha));
        }
        for (std::size_t i = 0; i < capabilities.size(); ++i)
            if (enabled_[i]) glEnable(capabilities[i]);
            else glDisable(capabilities[i]);
        glLogicOp(GLenum(logic_op_));
        glPolygonMode(GL_FRONT_AND_BACK, GLenum(polygon_mode_[0]));
        glLineWidth(line_width_);
        for (std::size_t i = 0; i < pack_parameters.size(); ++i) glPixelStorei(pack_parameters[i], pack_[i]);
#ifdef GL_CLIP_ORIGIN
        if (has_clip_control_) glClipControl(GLenum(clip_origin_), GLenum(clip_depth_));
#endif
        if (pushed_group_) glPopDebugGroup();
    }

    /// Sets the state every pass of the library depends on, whatever the caller left: no blending,
    /// depth or stencil test, culling, logic op, scissor, dithering, depth clamp, line smoothing,
    /// primitive restart or clip distance; rasterisation on, every colour channel written, filled
    /// polygons, 1-pixel lines, GL's default clip control, tightly packed read-backs into client
    /// memory, no sampler objects on units [0, saved_units), and unit 0 active. Passes then enable
    /// what they use.
    void set_pass_state() const {
        for (std::size_t i = 0; i < capabilities.size(); ++i) glDisable(capabilities[i]);
        for (int i = 0; i < draw_buffers_; ++i) glDisablei(GL_BLEND, GLuint(i));
        for (int i = 0; i < viewports_; ++i) glDisablei(GL_SCISSOR_TEST, GLuint(i));
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glLineWidth(1.0f);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
        for (std::size_t i = 0; i < pack_parameters.size(); ++i) glPixelStorei(pack_parameters[i], pack_parameters[i] == GL_PACK_ALIGNMENT ? 1 : 0);
#ifdef GL_CLIP_ORIGIN
        if (has_clip_control_) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
#endif
        for (int u = 0; u < saved_units; ++u) glBindSampler(GLuint(u), 0);
        glActiveTexture(GL_TEXTURE0);
    }

private:
    static constexpr std::size_t max_viewports = 16, max_draw_buffers = 16;
    /// Capabilities that change what a pass writes (GL_BLEND and GL_SCISSOR_TEST, per buffer and per
    /// viewport, are apart). Dithering may move 8-bit values; unwritten clip distances are undefined.
    static constexpr std::array<GLenum, 19> capabilities = {
        GL_DEPTH_TEST,      GL_STENCIL_TEST,    GL_CULL_FACE,       GL_COLOR_LOGIC_OP,  GL_RASTERIZER_DISCARD,
        GL_DITHER,          GL_DEPTH_CLAMP,     GL_LINE_SMOOTH,     GL_POLYGON_SMOOTH,  GL_PRIMITIVE_RESTART,
        GL_PRIMITIVE_RESTART_FIXED_INDEX,       GL_CLIP_DISTANCE0,  GL_CLIP_DISTANCE1,  GL_CLIP_DISTANCE2,
        GL_CLIP_DISTANCE3,  GL_CLIP_DISTANCE4,  GL_CLIP_DISTANCE5,  GL_CLIP_DISTANCE6,  GL_CLIP_DISTANCE7};
    static constexpr std::array<GLenum, 8> pack_parameters = {GL_PACK_ALIGNMENT,   GL_PACK_ROW_LENGTH,  GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS,
                                                              GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_IMAGES, GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST};

    static void set_enabled(GLenum cap, GLuint index, GLboolean on) {
        if (on) glEnablei(cap, index);
        else glDisablei(cap, index);
    }

    /// Names the library's GL calls in a debug group (KHR_debug, core in GL 4.3), for the caller's
    /// debug callback and frame debuggers; skipped where the caller's groups fill the stack.
    void push_debug_group(const char* label) {
        GLint depth = 0, max_depth = 0;
        glGetIntegerv(GL_DEBUG_GROUP_STACK_DEPTH, &depth);
        glGetIntegerv(GL_MAX_DEBUG_GROUP_STACK_DEPTH, &max_depth);
        if (depth >= max_depth) return;
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, label);
        pushed_group_ = true;
    }

    struct unit_bindings {
        GLint texture_2d = 0, texture_array = 0, sampler = 0;
    };
    struct blend_state {
        GLboolean enabled = GL_FALSE;
        std::array<GLboolean, 4> mask{};
        GLint equation_rgb = 0, equation_alpha = 0, src_rgb = 0, dst_rgb = 0, src_alpha = 0, dst_alpha = 0;
    };
    struct image_binding {
        GLint name = 0, level = 0, layer = 0, access = GL_READ_ONLY, format = GL_R8;
        GLboolean layered = GL_FALSE;
    };

    struct storage_binding {
        GLint name = 0;
        GLint64 start = 0, size = 0;
    };

    caller_errors_kept caller_errors_; // first: taken before anything else, raised again after everything is restored
    GLint program_ = 0, draw_fbo_ = 0, read_fbo_ = 0, vao_ = 0, array_buffer_ = 0, storage_buffer_ = 0, pack_buffer_ = 0;
    std::array<storage_binding, saved_storage_bindings> storage_{};
    std::array<image_binding, saved_images> images_{};
    GLint active_texture_ = GL_TEXTURE0;
    int unit_count_ = saved_units;
    std::array<unit_bindings, max_saved_units> units_{};
    int viewports_ = 0, draw_buffers_ = 0;
    std::array<std::array<GLfloat, 4>, max_viewports> viewport_{};
    std::array<GLboolean, max_viewports> scissor_test_{};
    std::array<blend_state, max_draw_buffers> blend_{};
    std::array<GLboolean, capabilities.size()> enabled_{};
    GLint logic_op_ = GL_COPY;
    std::array<GLint, 2> polygon_mode_{GL_FILL, GL_FILL};
    GLfloat line_width_ = 1.0f;
    std::array<GLint, pack_parameters.size()> pack_{};
    bool has_clip_control_ = false;
    GLint clip_origin_ = 0, clip_depth_ = 0;
    bool pushed_group_ = false;
};

} // namespace hairshadow::gl
