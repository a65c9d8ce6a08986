#pragma once
/// @file
/// A headless EGL context with no surface: on a GPU through EGL's device platform (glvnd and the
/// vendor's EGL, e.g. an NVIDIA GPU with no display), else Mesa's surfaceless platform. Include the GL
/// loader, then this header; link EGL.

#include <hairshadow/gl/context/context.hpp>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>
#include <vector>

namespace hairshadow::gl {

/// An OpenGL core context on the first EGL device that gives one, without a surface.
class egl_context final : public headless_context {
public:
    explicit egl_context(int major = 4, int minor = 5) {
        display_ = open_display();
        if (display_ == EGL_NO_DISPLAY) throw gl_error("EGL: no device or surfaceless display");
        EGLint egl_major = 0, egl_minor = 0;
        if (!eglInitialize(display_, &egl_major, &egl_minor)) throw gl_error("EGL: eglInitialize failed");
        if (!eglBindAPI(EGL_OPENGL_API)) throw gl_error("EGL: the display offers no desktop OpenGL");
        const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        eglChooseConfig(display_, config_attributes, &config, 1, &count); // may find none: surfaceless needs no config
        const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        context_ = eglCreateContext(display_, count > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, context_attributes);
        if (context_ == EGL_NO_CONTEXT)
            throw gl_error("EGL: cannot create a core " + std::to_string(major) + "." + std::to_string(minor) + " context");
        make_current();
    }
    ~egl_context() override {
        if (display_ != EGL_NO_DISPLAY) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
            eglTerminate(display_);
        }
    }
    egl_context(const egl_context&) = delete;
    egl_context& operator=(const egl_context&) = delete;

    void make_current() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) throw gl_error("EGL: cannot make the context current");
    }
    loader_function loader() const override { return +[](const char* name) -> proc { return eglGetProcAddress(name); }; }

private:
    static EGLDisplay open_display() {
        auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (query_devices && platform_display) {
            EGLDeviceEXT devices[16];
            EGLint count = 0;
            if (query_devices(16, devices, &count))
                for (EGLint i = 0; i < count; ++i) {
                    EGLDisplay d = platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                    EGLint a, b;
                    if (d != EGL_NO_DISPLAY && eglInitialize(d, &a, &b)) return d;
                }
        }
        if (platform_display) return platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        return EGL_NO_DISPLAY;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

} // namespace hairshadow::gl
