#pragma once
// The command's GL back end, behind an interface so that the command builds without GL: a headless
// context (OSMesa or EGL) and any method's maps built on it. gl_backend.cpp implements it;
// gl_backend_missing.cpp stands in where the build found no GL loader or context library.

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>
#include <hairshadow/shading/camera.hpp>
#include <hairshadow/shading/image.hpp>
#include <hairshadow/shading/scene.hpp>
#include <hairshadow/shading/transparency.hpp>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hairshadow::gl {
class headless_context;
}

namespace cli {

class gl_backend {
public:
    /// Opens a context of `kind` ("osmesa" or "egl") and loads GL, building maps on `path` ("compute"
    /// or "raster"; "": compute); throws hairshadow::error when it cannot (gl::feature_error below GL
    /// 4.3, or for compute where the context lacks what it needs).
    static std::unique_ptr<gl_backend> open(const std::string& kind, const std::string& path = "");
    /// The same on a context the caller made (and keeps alive longer than the back end), with GL
    /// loaded; makes it current.
    static std::unique_ptr<gl_backend> open_on(hairshadow::gl::headless_context& context, const std::string& path = "");
    virtual ~gl_backend() = default;
    /// Makes the context current on the calling thread (for a program with several back ends).
    virtual void make_current() = 0;
    /// "OpenGL <version> on <renderer>, <path> build".
    virtual std::string description() const = 0;
    /// Uploads the model that build() draws.
    virtual void set_model(const hairshadow::hair_model& model) = 0;
    /// Builds a method's maps on the GPU; returns the wall time in milliseconds of a second build (the
    /// first compiles the driver's shader variants), until the GPU finished.
    virtual double build(const hairshadow::method_spec& spec, const hairshadow::light_space& light, const hairshadow::raster_options& options) = 0;
    /// Builds the last built maps again; returns the wall time in milliseconds, until the GPU finished.
    /// The GPU's own time for it, by a GL_TIME_ELAPSED query, is last_gpu_ms() after.
    virtual double last_gpu_ms() const = 0;
    virtual double rebuild(const hairshadow::light_space& light, const hairshadow::raster_options& options) = 0;
    /// Builds the maps of every spec for one light, each with a light pass of its own (`shared` false)
    /// or all from one shared light pass; returns the wall time in milliseconds until the GPU
    /// finished. The maps and the pass are made at the first call and reused after.
    virtual double build_all(const std::vector<hairshadow::method_spec>& specs, const hairshadow::light_space& light,
                             const hairshadow::raster_options& options, bool shared) = 0;
    /// Transmittance at each point through the last built maps' GLSL look-up.
    virtual std::vector<float> transmittance(std::span<const glm::vec3> points, float depth_bias) = 0;
    /// Bytes of the last built maps' textures.
    virtual std::size_t memory_bytes() = 0;
    /// Renders `sc` from `cam` on GL: each light's maps (one per frustum in `spaces`) built there and
    /// read by the GL renderer's passes, the hair drawn with `mode` and `hair_opacity`
    /// (gl::scene_renderer::set_transparency).
    virtual hairshadow::image render_scene(const hairshadow::scene& sc, const hairshadow::camera& cam, const hairshadow::method_spec& spec,
                                           const std::vector<hairshadow::light_space>& spaces, const hairshadow::raster_options& options,
                                           hairshadow::transparency mode, float hair_opacity) = 0;
    /// Depth-peeling layers of the last render_scene with transparency::exact.
    virtual int peeled_layers() const = 0;
    /// The last built maps read back for CPU queries.
    virtual std::unique_ptr<hairshadow::any_shadow_map> to_cpu() = 0;
};

} // namespace cli
