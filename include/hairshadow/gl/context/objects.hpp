#pragma once
/// @file
/// RAII owners of GL objects, and shader programs whose compile and link logs become exceptions.

#include <hairshadow/gl/context/error.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hairshadow::gl {

/// Owns one GL name; `Delete` frees it.
template <void (*Delete)(GLuint)>
class object {
public:
    object() = default;
    explicit object(GLuint name) : name_(name) {}
    ~object() { reset(); }
    object(object&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    object& operator=(object&& o) noexcept {
        if (this != &o) reset(), name_ = std::exchange(o.name_, 0);
        return *this;
    }
    object(const object&) = delete;
    object& operator=(const object&) = delete;
    GLuint get() const noexcept { return name_; }
    explicit operator bool() const noexcept { return name_ != 0; }
    void reset() noexcept {
        if (name_) Delete(name_);
        name_ = 0;
    }

private:
    GLuint name_ = 0;
};

namespace detail {
inline void delete_buffer(GLuint n) { glDeleteBuffers(1, &n); }
inline void delete_texture(GLuint n) { glDeleteTextures(1, &n); }
inline void delete_framebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void delete_vertex_array(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void delete_shader(GLuint n) { glDeleteShader(n); }
inline void delete_program(GLuint n) { glDeleteProgram(n); }
inline void delete_query(GLuint n) { glDeleteQueries(1, &n); }
inline void delete_renderbuffer(GLuint n) { glDeleteRenderbuffers(1, &n); }

} // namespace detail

using buffer = object<detail::delete_buffer>;
using texture = object<detail::delete_texture>;
using framebuffer = object<detail::delete_framebuffer>;
using vertex_array = object<detail::delete_vertex_array>;
using shader = object<detail::delete_shader>;
using program = object<detail::delete_program>;
using query = object<detail::delete_query>;
using renderbuffer = object<detail::delete_renderbuffer>;

/// Owns a fence (glFenceSync): has the GPU passed the commands issued before it?
class fence_sync {
public:
    fence_sync() = default;
    ~fence_sync() { reset(); }
    fence_sync(fence_sync&& o) noexcept : sync_(std::exchange(o.sync_, nullptr)) {}
    fence_sync& operator=(fence_sync&& o) noexcept {
        if (this != &o) reset(), sync_ = std::exchange(o.sync_, nullptr);
        return *this;
    }
    fence_sync(const fence_sync&) = delete;
    fence_sync& operator=(const fence_sync&) = delete;
    /// A fence after every command issued so far (the last one placed is dropped).
    void place() {
        reset();
        sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    }
    /// True when a fence is placed and the GPU has passed it. Never waits; flushes the commands
    /// before it, so that it will pass.
    bool passed() const {
        if (!sync_) return false;
        const GLenum state = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
        return state == GL_ALREADY_SIGNALED || state == GL_CONDITION_SATISFIED;
    }
    void reset() noexcept {
        if (sync_) glDeleteSync(sync_);
        sync_ = nullptr;
    }

private:
    GLsync sync_ = nullptr;
};

inline buffer make_buffer() {
    GLuint n = 0;
    glGenBuffers(1, &n);
    return buffer(n);
}
inline texture make_texture() {
    GLuint n = 0;
    glGenTextures(1, &n);
    return texture(n);
}
/// A 2D texture of one level, `format` and size, read texel by texel: nearest filtering, which
/// integer formats need to be complete.
inline texture make_texture_2d(GLenum format, int width, int height) {
    auto t = make_texture();
    glBindTexture(GL_TEXTURE_2D, t.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}
inline framebuffer make_framebuffer() {
    GLuint n = 0;
    glGenFramebuffers(1, &n);
    return framebuffer(n);
}
inline renderbuffer make_renderbuffer() {
    GLuint n = 0;
    glGenRenderbuffers(1, &n);
    return renderbuffer(n);
}
inline vertex_array make_vertex_array() {
    GLuint n = 0;
    glGenVertexArrays(1, &n);
    return vertex_array(n);
}

/// Compiles one stage from pieces as given (the version line first: compile_stage adds it); throws
/// gl_error with the log.
inline shader compile_shader(GLenum stage, const std::vector<std::string_view>& pieces, const std::string& name) {
    shader s(glCreateShader(stage));
    std::vector<const GLchar*> sources;
    std::vector<GLint> lengths;
    for (auto p : pieces)
        if (!p.empty()) sources.push_back(p.data()), lengths.push_back(GLint(p.size())); // an empty view may hold no pointer at all
    glShaderSource(s.get(), GLsizei(sources.size()), sources.data(), lengths.data());
    glCompileShader(s.get());
    GLint ok = 0;
    glGetShaderiv(s.get(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(s.get(), GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(s.get(), length, nullptr, log.data());
        throw gl_error("cannot compile " + name + ":\n" + log);
    }
    return s;
}

/// The version line every program of the library starts with: GLSL 4.30 core (GL 4.3).
inline constexpr std::string_view glsl_version = "#version 430 core\n";

/// Compiles one stage of the library's: the version line, then `defines`, then `pieces` (snippets);
/// throws gl_error with the log. Every program the library builds starts here.
inline shader compile_stage(GLenum stage, std::string_view defines, std::vector<std::string_view> pieces, const std::string& name) {
    pieces.insert(pieces.begin(), {glsl_version, defines});
    return compile_shader(stage, pieces, name);
}

/// Links stages into a program; throws gl_error with the log.
inline program link_program(const std::vector<const shader*>& stages, const std::string& name) {
    program p(glCreateProgram());
    for (const auto* s : stages) glAttachShader(p.get(), s->get());
    glLinkProgram(p.get());
    GLint ok = 0;
    glGetProgramiv(p.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(p.get(), GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(p.get(), length, nullptr, log.data());
        throw gl_error("cannot link " + name + ":\n" + log);
    }
    return p;
}

} // namespace hairshadow::gl
