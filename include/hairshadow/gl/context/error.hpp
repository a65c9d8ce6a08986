#pragma once
/// @file
/// Errors of the GL back end. Include a GL 4.3+ loader (glad's <glad/gl.h>) before any GL header.

#include <hairshadow/core/error.hpp>

#include <string>

namespace hairshadow::gl {

/// A GL call failed, a shader did not compile or link (what() holds the log), or a context could not
/// be made.
class gl_error : public error {
public:
    using error::error;
};

/// The context lacks a feature the method needs; what() names it.
class feature_error : public gl_error {
public:
    using gl_error::gl_error;
};

/// Throws gl_error naming `where` if GL has recorded an error.
inline void check(const char* where) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    const char* name = e == GL_INVALID_ENUM ? "GL_INVALID_ENUM"
                       : e == GL_INVALID_VALUE ? "GL_INVALID_VALUE"
                       : e == GL_INVALID_OPERATION ? "GL_INVALID_OPERATION"
                       : e == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                       : e == GL_OUT_OF_MEMORY ? "GL_OUT_OF_MEMORY"
                                               : "an unknown GL error";
    throw gl_error(std::string(where) + ": " + name);
}

} // namespace hairshadow::gl
