// The command's GL back end over the library's GL registry.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <hairshadow/gl/context/egl_context.hpp>
#include <hairshadow/gl/context/osmesa_context.hpp>
#include <hairshadow/gl/maps/registry.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>

#include "gl_backend.hpp"

#include <chrono>
#include <optional>

namespace cli {
namespace {

using namespace hairshadow;

class gl_backend_impl final : public gl_backend {
public:
    gl_backend_impl(const std::string& kind, const std::string& path) {
        // Asks for core 3.3, which drivers answer with their newest core version; each method then
        // checks the version and limits it needs and names what is missing.
        if (kind == "osmesa") owned_ = std::make_unique<gl::osmesa_context>(3, 3);
        else if (kind == "egl") owned_ = std::make_unique<gl::egl_context>(3, 3);
        else throw argument_error("unknown GL context '" + kind + "'; valid: osmesa, egl");
        context_ = owned_.get();
        if (!gladLoadGL(context_->loader())) throw gl::gl_error("cannot load the GL functions of the " + kind + " context");
        choose_path(path);
    }
    gl_backend_impl(gl::headless_context& context, const std::string& path) : context_(&context) {
        context_->make_current();
        choose_path(path);
    }
    void make_current() override { context_->make_current(); }
    std::string description() const override { return context_->description() + ", " + std::string(gl::to_string(path_)) + " build"; }
    void set_model(const hair_model& model) override { mesh_.emplace(model); }
    double build(const method_spec& spec, const light_space& light, const raster_options& options) override {
        if (!mesh_) throw argument_error("no model to draw");
        maps_ = make(spec);
        maps_->build(*mesh_, light, options); // drivers compile shader variants at the first draw: time the second build
        return rebuild(light, options);
    }
    double rebuild(const light_space& light, const raster_options& options) override {
        if (!mesh_) throw argument_error("no model to draw");
        if (!timer_) {
            GLuint name = 0;
            glGenQueries(1, &name);
            timer_ = gl::query(name);
        }
        const auto start = std::chrono::steady_clock::now();
        glBeginQuery(GL_TIME_ELAPSED, timer_.get());
        built().build(*mesh_, light, options);
        glEndQuery(GL_TIME_ELAPSED);
        const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        GLuint64 ns = 0;
        glGetQueryObjectui64v(timer_.get(), GL_QUERY_RESULT, &ns);
        gpu_ms_ = double(ns) * 1e-6;
        return wall;
    }
    double last_gpu_ms() const override { return gpu_ms_; }
    double build_all(const std::vector<method_spec>& specs, const light_space& light, const raster_options& options, bool shared) override {
        if (!mesh_) throw argument_error("no model to draw");
        if (all_maps_.size() != specs.size()) {
            all_maps_.clear();
            for (const auto& spec : specs) all_maps_.push_back(make(spec));
        }
        if (!pass_) pass_.emplace(path_);
        const auto start = std::chrono::steady_clock::now();
        if (shared) pass_->run(*mesh_, light, options);
        for (auto& maps : all_maps_) {
            if (shared) maps->build(*pass_);
            else maps->build(*mesh_, light, options);
        }
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    std::vector<float> transmittance(std::span<const glm::vec3> points, float depth_bias) override {
        return built().transmittance(points, depth_bias);
    }
    std::unique_ptr<any_shadow_map> to_cpu() override { return built().to_cpu(); }
    std::size_t memory_bytes() override { return built().memory_bytes(); }
    image render_scene(const scene& sc, const camera& cam, const method_spec& spec, const std::vector<light_space>& spaces,
                       const raster_options& options, transparency mode, float hair_opacity) override {
        const gl::hair_mesh mesh(sc.hair);
        gl::scene_renderer renderer(sc);
        std::vector<std::unique_ptr<gl::any_gl_shadow_map>> maps;
        for (std::size_t i = 0; i < spaces.size(); ++i) {
            maps.push_back(make(spec));
            maps.back()->build(mesh, spaces[i], options);
            renderer.add_light(sc.lights[i], *maps.back());
        }
        renderer.set_transparency(mode, hair_opacity);
        auto picture = renderer.render(cam);
        peeled_layers_ = renderer.peeled_layers();
        return picture;
    }
    int peeled_layers() const override { return peeled_layers_; }

private:
    void choose_path(const std::string& path) {
        if (!path.empty() && path != "compute" && path != "raster") throw argument_error("unknown GL build path '" + path + "'; valid: compute, raster");
        path_ = path.empty() ? gl::default_build_path() : path == "compute" ? gl::build_path::compute : gl::build_path::raster;
        gl::require_version(4, 3, "the GL back end"); // both paths: before pointing from one to the other
        if (path_ == gl::build_path::compute) gl::require_compute_path(path.empty() ? "the default --gl-path (compute)" : "--gl-path compute", "use --gl-path raster");
    }
    std::unique_ptr<gl::any_gl_shadow_map> make(const method_spec& spec) const {
        auto maps = gl::make_gl_shadow_map(spec);
        maps->set_build_path(path_);
        return maps;
    }
    gl::any_gl_shadow_map& built() {
        if (!maps_) throw argument_error("no maps built on GL");
        return *maps_;
    }
    std::unique_ptr<gl::headless_context> owned_; ///< the context this back end opened, if it did
    gl::headless_context* context_ = nullptr;
    gl::build_path path_ = gl::build_path::raster;
    std::optional<gl::hair_mesh> mesh_;
    std::unique_ptr<gl::any_gl_shadow_map> maps_;
    std::vector<std::unique_ptr<gl::any_gl_shadow_map>> all_maps_;
    std::optional<gl::light_pass> pass_;
    int peeled_layers_ = 0;
    gl::query timer_;
    double gpu_ms_ = 0.0;
};

} // namespace

std::unique_ptr<gl_backend> gl_backend::open(const std::string& kind, const std::string& path) {
    return std::make_unique<gl_backend_impl>(kind, path);
}

std::unique_ptr<gl_backend> gl_backend::open_on(gl::headless_context& context, const std::string& path) {
    return std::make_unique<gl_backend_impl>(context, path);
}

} // namespace cli
