#pragma once
/// @file
/// Headless GL contexts behind one small interface: OSMesa (llvmpipe, core 4.5; gone from Mesa 25.1)
/// and EGL (a GPU's device platform, or Mesa's surfaceless one). The same program runs in CI on
/// llvmpipe and on an NVIDIA GPU with no display.

#include <hairshadow/gl/context/error.hpp>

#include <memory>
#include <string>

namespace hairshadow::gl {

/// A current GL context with no window.
class headless_context {
public:
    using proc = void (*)();
    using loader_function = proc (*)(const char*);
    virtual ~headless_context() = default;
    /// Makes the context current on the calling thread.
    virtual void make_current() = 0;
    /// GL's function look-up, for the loader: gladLoadGL(context.loader()).
    virtual loader_function loader() const = 0;
    /// "OpenGL <version> on <renderer>".
    std::string description() const {
        return std::string("OpenGL ") + reinterpret_cast<const char*>(glGetString(GL_VERSION)) + " on " +
               reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    }
};

/// The context's GL version as major * 10 + minor.
inline int gl_version() {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    return major * 10 + minor;
}

/// Throws feature_error unless the current context is GL `major.minor` or newer.
inline void require_version(int major, int minor, const std::string& what) {
    if (gl_version() < major * 10 + minor)
        throw feature_error(what + " needs OpenGL " + std::to_string(major) + "." + std::to_string(minor) + "; the context has " +
                            std::to_string(gl_version() / 10) + "." + std::to_string(gl_version() % 10));
}

} // namespace hairshadow::gl
