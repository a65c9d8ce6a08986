#pragma once
/// @file
/// Methods chosen at run time: any method spec becomes a shadow map behind one interface. This header
/// instantiates every supported size of every method, so include it only where specs are parsed (the
/// command line, the benchmarks); code that knows its method at compile time uses the templates.
///
/// Each file that includes it compiles every method's builds, which is slow. A project that parses
/// specs in several files can compile the registry once: define HAIRSHADOW_SEPARATE_REGISTRY in every
/// file (make_shadow_map is then only declared), and HAIRSHADOW_REGISTRY_IMPLEMENTATION as well in
/// exactly one (which then defines it); gl/maps/registry.hpp does the same with
/// HAIRSHADOW_GL_REGISTRY_IMPLEMENTATION, and then instantiates no CPU build (its read-backs go into
/// maps that make_shadow_map makes).

#include <hairshadow/methods/published.hpp>
#include <hairshadow/methods/spec.hpp>
#include <hairshadow/raster/rasterizer.hpp>
#include <hairshadow/reference/compressed_deep_shadow_map.hpp>
#include <hairshadow/reference/deep_shadow_map.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

/// inline, unless the registry is compiled once (HAIRSHADOW_SEPARATE_REGISTRY).
#ifndef HAIRSHADOW_REGISTRY_LINKAGE
#ifdef HAIRSHADOW_SEPARATE_REGISTRY
#define HAIRSHADOW_REGISTRY_LINKAGE
#else
#define HAIRSHADOW_REGISTRY_LINKAGE inline
#endif
#endif

namespace hairshadow {

namespace detail {
/// One address per type, the same in every translation unit (an inline variable): identifies a type
/// without RTTI.
template <class T>
inline constexpr char type_tag = 0;

/// 64-bit FNV-1a of `size` bytes, continuing from `h`.
inline std::uint64_t fnv1a(const void* bytes, std::size_t size, std::uint64_t h = 14695981039346656037ull) noexcept {
    const auto* p = static_cast<const unsigned char*>(bytes);
    for (std::size_t i = 0; i < size; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}
} // namespace detail

/// Any shadow map, built from fragments and queried like the others.
class any_shadow_map : public map_queries<any_shadow_map> {
public:
    virtual ~any_shadow_map() = default;
    /// Builds straight from the model, tile by tile (the exact reference streamed: no buffer of the
    /// map's fragments). The methods keep their working memory for the next build.
    virtual void build(const hair_model& model, const light_space& light, const raster_options& options = {}) = 0;
    virtual void build(const fragment_buffer& fragments, const light_space& light, const execution& exec = {}) = 0;
    virtual float optical_depth(int x, int y, float depth) const = 0;
    virtual const light_space& light() const = 0;
    virtual std::size_t memory_bytes() const = 0;
    /// Layers, clusters or slices the method stores per texel; 0 for the exact map and for a fixed
    /// fibre density (a depth map only).
    virtual int layer_count() const = 0;
    /// Bytes per texel and global bytes, known before building; nullopt for the exact map, whose size
    /// depends on the fragments.
    virtual std::optional<std::size_t> memory_bytes_at(int resolution) const = 0;
    /// Maps the method stores per texel (layers, bins or slabs; 0 for the exact map), for inspection.
    virtual int stored_maps() const = 0;
    /// Fragments the last build summed.
    virtual std::size_t fragment_count() const = 0;
    /// Optical depth stored in map k of texel (x, y).
    virtual float stored_optical_depth(int x, int y, int k) const = 0;
    /// A hash (64-bit FNV-1a) of everything the maps hold, texel by texel: every byte of each texel's
    /// state and layers and the whole-map extent; for the exact map each texel's fragment depths and
    /// optical depths, or its compressed function's vertices. Equal maps hash equal in any run, so a
    /// hash shows that two builds (two versions, two machines of one byte order) made the same maps;
    /// `hairshadow bench` prints it.
    virtual std::uint64_t maps_hash() const = 0;
    const method_spec& spec() const noexcept { return spec_; }
    using map_queries<any_shadow_map>::transmittance;

    /// The composition behind this map where it is `Method` (a shadow_method; for the exact reference,
    /// once built, deep_shadow_map and, where compressed, compressed_deep_shadow_map), else null: for code
    /// that knows the type, such as the GL registry, which puts maps read back from GL into a map the
    /// CPU registry made rather than instantiating every CPU build a second time.
    template <class Method>
    Method* method_if() noexcept {
        return static_cast<Method*>(method_address(&detail::type_tag<Method>));
    }

protected:
    explicit any_shadow_map(method_spec spec) : spec_(std::move(spec)) {}
    /// The address of the composition if `tag` is its detail::type_tag, else null.
    virtual void* method_address(const void* tag) noexcept {
        (void)tag;
        return nullptr;
    }

private:
    method_spec spec_;
};

namespace detail {

template <class Method>
class method_map final : public any_shadow_map {
public:
    method_map(method_spec spec, Method method) : any_shadow_map(std::move(spec)), method_(std::move(method)) {}
    void build(const hair_model& model, const light_space& light, const raster_options& options) override { method_.build(model, light, options); }
    void build(const fragment_buffer& fragments, const light_space& light, const execution& exec) override { method_.build(fragments, light, exec); }
    float optical_depth(int x, int y, float depth) const override { return method_.optical_depth(x, y, depth); }
    const light_space& light() const override { return method_.light(); }
    std::size_t memory_bytes() const override { return method_.memory_bytes(); }
    int layer_count() const override { return Method::stored_maps == 0 ? 0 : Method::layer_count; }
    std::optional<std::size_t> memory_bytes_at(int resolution) const override {
        return std::size_t(resolution) * std::size_t(resolution) * Method::texel_bytes() + placement_global_bytes<typename Method::placement_type>();
    }
    int stored_maps() const override { return Method::stored_maps; }
    std::size_t fragment_count() const override { return method_.fragment_count(); }
    float stored_optical_depth(int x, int y, int k) const override { return method_.stored_optical_depth(x, y, k); }
    std::uint64_t maps_hash() const override {
        static_assert(std::is_trivially_copyable_v<typename Method::texel_maps>);
        const int res = method_.light().resolution();
        std::uint64_t h = fnv1a(&method_.map_extent(), sizeof(depth_extent));
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) h = fnv1a(&method_.texel(x, y), sizeof(typename Method::texel_maps), h); // every byte a value (padding_free)
        return h;
    }
    const Method& method() const noexcept { return method_; }

private:
    void* method_address(const void* tag) noexcept override { return tag == &type_tag<Method> ? &method_ : nullptr; }

    Method method_;
};

class reference_map final : public any_shadow_map {
public:
    reference_map(method_spec spec, exact_reference reference) : any_shadow_map(std::move(spec)), tolerance_(reference.tolerance) {}
    /// Streamed tile by tile from the model: the compressed map never holds the exact one.
    void build(const hair_model& model, const light_space& light, const raster_options& options) override {
        exact_.reset(), compressed_.reset(); // the old map's memory is free before the new one is made
        if (tolerance_) compressed_.emplace(model, light, *tolerance_, options, build_progress{}, &workspace_);
        else exact_.emplace(model, light, options, build_progress{}, &workspace_);
    }
    void build(const fragment_buffer& fragments, const light_space& light, const execution& exec) override {
        exact_.reset(), compressed_.reset();
        exact_.emplace(fragments, light, exec);
        if (tolerance_) compressed_.emplace(*exact_, *tolerance_, exec);
    }
    float optical_depth(int x, int y, float depth) const override {
        if (compressed_) return compressed_->optical_depth(x, y, depth);
        return exact_ ? exact_->optical_depth(x, y, depth) : 0.0f; // not built: no shadow, like an unbuilt shadow_method
    }
    const light_space& light() const override {
        if (compressed_) return compressed_->light();
        if (!exact_) throw argument_error("the exact map has no light before build()");
        return exact_->light();
    }
    std::size_t memory_bytes() const override {
        if (compressed_) return compressed_->memory_bytes();
        return exact_ ? exact_->memory_bytes() : 0;
    }
    int layer_count() const override { return 0; }
    std::optional<std::size_t> memory_bytes_at(int) const override { return std::nullopt; }
    int stored_maps() const override { return 0; }
    std::size_t fragment_count() const override {
        if (compressed_) return compressed_->fragment_count();
        return exact_ ? exact_->fragment_count() : 0;
    }
    float stored_optical_depth(int, int, int) const override { return 0.0f; }
    std::uint64_t maps_hash() const override {
        std::uint64_t h = detail::fnv1a(nullptr, 0);
        if (!exact_ && !compressed_) return h;
        const int res = light().resolution();
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) {
                if (compressed_) {
                    const auto v = compressed_->vertices(x, y);
                    const std::uint64_t n = v.size();
                    h = detail::fnv1a(v.data(), v.size_bytes(), detail::fnv1a(&n, sizeof n, h)); // two floats a vertex, no padding
                } else {
                    const auto d = exact_->depths(x, y), o = exact_->optical_depths(x, y);
                    const std::uint64_t n = d.size();
                    h = detail::fnv1a(o.data(), o.size_bytes(), detail::fnv1a(d.data(), d.size_bytes(), detail::fnv1a(&n, sizeof n, h)));
                }
            }
        return h;
    }

private:
    /// method_if gives the built deep_shadow_map (its fragments; only where built from a fragment
    /// buffer or not compressed) and, where compressed, the compressed_deep_shadow_map (its vertices).
    void* method_address(const void* tag) noexcept override {
        if (tag == &type_tag<deep_shadow_map> && exact_) return &*exact_;
        if (tag == &type_tag<compressed_deep_shadow_map> && compressed_) return &*compressed_;
        return nullptr;
    }

    std::optional<float> tolerance_;   ///< Lokovic-Veach compression's, if compressed
    streamed_workspace workspace_;     ///< kept between builds from a model
    std::optional<deep_shadow_map> exact_;
    std::optional<compressed_deep_shadow_map> compressed_;
};

} // namespace detail

/// Makes the (not yet built) shadow map of a spec (parse_method_spec's); throws spec_error for one no
/// registered family names.
#if defined(HAIRSHADOW_SEPARATE_REGISTRY) && !defined(HAIRSHADOW_REGISTRY_IMPLEMENTATION)
std::unique_ptr<any_shadow_map> make_shadow_map(const method_spec& spec); // defined in the one implementing file
#else
HAIRSHADOW_REGISTRY_LINKAGE std::unique_ptr<any_shadow_map> make_shadow_map(const method_spec& spec) {
    std::unique_ptr<any_shadow_map> map;
    visit_method(spec, [&]<class Method>(Method method) {
        if constexpr (std::is_same_v<Method, exact_reference>) map = std::make_unique<detail::reference_map>(spec, method);
        else map = std::make_unique<detail::method_map<Method>>(spec, std::move(method));
    });
    if (!map) throw spec_error("unsupported method spec '" + spec.text + "'; valid: " + method_grammar());
    return map;
}
#endif

/// Parses and makes in one step.
inline std::unique_ptr<any_shadow_map> make_shadow_map(std::string_view spec) { return make_shadow_map(parse_method_spec(spec)); }

} // namespace hairshadow
