#pragma once
/// @file
/// Methods chosen at run time on GL: any method spec with a GL twin becomes maps built on the GPU,
/// queried through the GLSL look-up or read back for CPU queries. Like methods/registry.hpp this
/// instantiates every supported size; include it only where specs are parsed, or compile it once
/// (HAIRSHADOW_SEPARATE_REGISTRY with HAIRSHADOW_GL_REGISTRY_IMPLEMENTATION, as methods/registry.hpp says).

#include <hairshadow/gl/maps/maps.hpp>
#include <hairshadow/gl/lookup/point_queries.hpp>
#include <hairshadow/methods/registry.hpp>

#include <memory>
#include <optional>
#include <stdexcept>
#include <type_traits>

namespace hairshadow::gl {

/// Any method's maps on GL.
class any_gl_shadow_map {
public:
    virtual ~any_gl_shadow_map() = default;
    /// The path build(mesh, light, options) takes (maps_base::set_build_path); build(pass) takes the pass's.
    virtual void set_build_path(build_path path) = 0;
    virtual build_path path() const = 0;
    /// Draws the maps of `mesh` seen from `light`; returns when the GPU has finished.
    virtual void build(const hair_mesh& mesh, const light_space& light, const raster_options& options = {}) = 0;
    /// The same from a light pass that has run, shared with other methods for its light.
    virtual void build(const light_pass& pass) = 0;
    /// Transmittance at each point by the GLSL look-up hs_transmittance, each point moved `depth_bias`
    /// towards the light (query_options::depth_bias); equal to the CPU query of the maps read back.
    virtual std::vector<float> transmittance(std::span<const glm::vec3> points, float depth_bias = 0.0f) = 0;
    /// The maps read back for CPU queries (filters, jitter, stored maps).
    virtual std::unique_ptr<any_shadow_map> to_cpu() = 0;
    /// Bytes of the textures the look-up reads.
    virtual std::size_t memory_bytes() const = 0;
    /// The method's GLSL look-up and its binding (as gl::maps<Method>), for user shaders and the renderer.
    virtual std::string lookup_source(std::string_view prefix = default_lookup_prefix) const = 0;
    virtual void bind_lookup(GLuint prog, int first_unit = 0, std::string_view prefix = default_lookup_prefix, float depth_bias = 0.0f) const = 0;
    /// Texture units bind_lookup binds.
    virtual int texture_units() const = 0;
    virtual const light_space& light() const = 0;
    const method_spec& spec() const noexcept { return spec_; }

protected:
    explicit any_gl_shadow_map(method_spec spec) : spec_(std::move(spec)) {}

private:
    method_spec spec_;
};

namespace detail {

template <class Method>
class gl_method_map final : public any_gl_shadow_map {
public:
    gl_method_map(method_spec spec, const Method& method) : any_gl_shadow_map(std::move(spec)), maps_(maps_of_method(method)) {}
    void set_build_path(build_path path) override { maps_.set_build_path(path); }
    build_path path() const override { return maps_.path(); }
    void build(const hair_mesh& mesh, const light_space& light, const raster_options& options) override {
        maps_.build(mesh, light, options);
        glFinish();
    }
    void build(const light_pass& pass) override {
        maps_.build(pass);
        glFinish();
    }
    std::vector<float> transmittance(std::span<const glm::vec3> points, float depth_bias) override {
        if (!queries_) queries_.emplace(maps_.lookup_source());
        return queries_->run(points, [&](GLuint prog) { maps_.bind_lookup(prog, 0, default_lookup_prefix, depth_bias); });
    }
    std::size_t memory_bytes() const override { return maps_.memory_bytes(); }
    std::string lookup_source(std::string_view prefix) const override { return maps_.lookup_source(prefix); }
    void bind_lookup(GLuint prog, int first_unit, std::string_view prefix, float depth_bias) const override {
        maps_.bind_lookup(prog, first_unit, prefix, depth_bias);
    }
    int texture_units() const override { return maps<Method>::texture_units; }
    const light_space& light() const override { return maps_.light(); }
    /// The maps read back, in a map of the CPU registry's making (make_shadow_map): where that registry
    /// is compiled apart (HAIRSHADOW_SEPARATE_REGISTRY), this file instantiates no CPU build.
    std::unique_ptr<any_shadow_map> to_cpu() override {
        auto map = make_shadow_map(spec());
        Method* method = map->template method_if<Method>();
        if (!method) throw std::logic_error("the CPU registry made another method for '" + spec().text + "'"); // both use visit_method
        *method = maps_.to_cpu();
        return map;
    }

private:
    maps<Method> maps_;
    std::optional<point_queries> queries_;
};

} // namespace detail

/// Makes the (not yet built) GL maps of a spec; throws spec_error for a spec without a GL twin (the
/// exact reference is CPU-only) and feature_error where the current context lacks what it needs.
#if defined(HAIRSHADOW_SEPARATE_REGISTRY) && !defined(HAIRSHADOW_GL_REGISTRY_IMPLEMENTATION)
std::unique_ptr<any_gl_shadow_map> make_gl_shadow_map(const method_spec& spec); // defined in the one implementing file
#else
HAIRSHADOW_REGISTRY_LINKAGE std::unique_ptr<any_gl_shadow_map> make_gl_shadow_map(const method_spec& spec) {
    std::unique_ptr<any_gl_shadow_map> map;
    visit_method(spec, [&]<class Method>(const Method& method) {
        if constexpr (std::is_same_v<Method, exact_reference>)
            throw spec_error("the exact reference (" + spec.text + ") has no GL back end; use --backend cpu");
        else map = std::make_unique<detail::gl_method_map<Method>>(spec, method);
    });
    if (!map) throw spec_error("unsupported method spec '" + spec.text + "'; valid: " + method_grammar());
    return map;
}
#endif

} // namespace hairshadow::gl
