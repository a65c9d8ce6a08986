#pragma once
/// @file
/// A core-profile OSMesa context (llvmpipe). Include the GL loader first, then this header; link
/// OSMesa (pkg-config osmesa).

#include <hairshadow/gl/context/context.hpp>

#include <GL/osmesa.h>

#include <vector>

namespace hairshadow::gl {

/// An OSMesa context of the requested core version, drawing into a tiny buffer (work goes to FBOs).
class osmesa_context final : public headless_context {
public:
    explicit osmesa_context(int major = 4, int minor = 5) : pixels_(4 * 4 * 4) {
        const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0, OSMESA_PROFILE,
                                  OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, major, OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!context_) throw gl_error("OSMesa: cannot create a core " + std::to_string(major) + "." + std::to_string(minor) + " context");
        make_current();
    }
    ~osmesa_context() override {
        if (context_) OSMesaDestroyContext(context_);
    }
    osmesa_context(const osmesa_context&) = delete;
    osmesa_context& operator=(const osmesa_context&) = delete;

    void make_current() override {
        if (!OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, 4, 4)) throw gl_error("OSMesa: cannot make the context current");
    }
    loader_function loader() const override { return +[](const char* name) -> proc { return OSMesaGetProcAddress(name); }; }

private:
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> pixels_;
};

} // namespace hairshadow::gl
