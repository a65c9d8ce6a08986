#pragma once
// The object behind hairshadow.ShadowMap: a method's maps from its spec, on the CPU or on GL, safe to
// use from several Python threads. Every member but the constructor, the destructor and the plain
// accessors is called without the GIL and touches no Python object: it takes the map's lock (builds
// exclusive, CPU queries shared, everything on GL exclusive), so no thread ever waits for the lock
// while holding the GIL.
#include "bindings.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <string>
#include <utility>
#include <vector>

namespace hairshadow::gl {
class any_gl_shadow_map;
class hair_mesh;
}

namespace hspy {

/// What the map's properties read, together under one lock.
struct map_summary {
    hairshadow::light_space light;
    std::size_t memory_bytes = 0;
    int layer_count = 0;
    std::size_t fragment_count = 0;
};

class shadow_map_handle {
public:
    /// Parses the spec (ValueError) and, on GL, opens the module's context (`context` "": the open
    /// one, else EGL) and checks the path. Called with the GIL.
    shadow_map_handle(const std::string& spec, const std::string& backend, const std::string& context, const std::string& gl_path);
    /// Called with the GIL; GL objects dropped on another thread than GL's wait for that thread's next GL call.
    ~shadow_map_handle();
    shadow_map_handle(const shadow_map_handle&) = delete;
    shadow_map_handle& operator=(const shadow_map_handle&) = delete;

    bool on_gl() const noexcept { return gl_path_.has_value(); }
    const std::string& spec_text() const noexcept { return spec_.text; }
    bool built() const noexcept { return built_; }
    std::string map_layout() const;

    // Without the GIL:
    void build(const hairshadow::hair_model& model, const hairshadow::light_spec& light, int resolution, std::optional<float> alpha, float wide,
               unsigned threads);
    void transmittance(std::span<const glm::vec3> points, std::span<float> out, const hairshadow::query_options& options,
                       const hairshadow::execution& exec);
    void along_ray(int x, int y, std::span<const float> depths, std::span<float> out, bool optical);
    /// The stored maps, [y][x][k].
    struct stored_values {
        std::vector<float> values;
        int resolution = 0, k = 0;
    };
    stored_values stored_maps();
    /// The exact map's fragments (depths, optical depth through each) or compressed vertices (depths, T).
    std::pair<std::vector<float>, std::vector<float>> fragments(int x, int y);
    map_summary summary();
    std::uint64_t maps_hash();

private:
    template <class F>
    auto reading(F&& f);
    void require_built() const;
    void check_texel(int x, int y) const;
    /// The CPU maps; on GL, the maps read back (once after each build). Under the lock.
    const hairshadow::any_shadow_map& cpu_maps();

    hairshadow::method_spec spec_;
    std::optional<std::string> gl_path_; ///< set on GL: "compute", "raster" or "" (the default)
    std::string context_kind_;
    std::unique_ptr<hairshadow::any_shadow_map> map_; ///< the CPU's maps, or GL's read back
    std::unique_ptr<hairshadow::gl::any_gl_shadow_map> gl_;
    std::unique_ptr<hairshadow::gl::hair_mesh> mesh_;
    std::atomic<bool> built_ = false;
    bool read_back_ = false; ///< map_ holds GL's last build
    std::shared_mutex mutex_;
};

} // namespace hspy
