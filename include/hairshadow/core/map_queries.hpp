#pragma once
/// @file
/// Transmittance queries shared by every shadow map: at a texel and depth, at world points (one or a
/// batch), with an optional 3x3 box filter (Kim & Neumann 2001, section 2) and half-texel jitter
/// (Sintorn & Assarsson 2009, section 3.3). A map provides optical_depth(x, y, depth) and light().

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <span>

namespace hairshadow {

/// How a world point is looked up.
struct query_options {
    /// Average the optical depth over the 3x3 texels around the point (at the point's depth), as Kim &
    /// Neumann filter their opacity maps; texels outside the map are left out of the average.
    bool box_filter = false;
    /// Move the look-up by up to half a texel in x and y, as Sintorn & Assarsson do against aliasing.
    /// The offset is a hash of the point's coordinates, so the same point always gets the same one.
    bool jitter = false;
    /// Move the query this far towards the light (linear depth), against self-shadowing acne.
    float depth_bias = 0.0f;

    /// Throws argument_error unless depth_bias is finite and within [-1, 1] (the map's whole depth).
    void check() const {
        if (!(depth_bias >= -1.0f && depth_bias <= 1.0f))
            throw argument_error("depth bias " + std::to_string(depth_bias) + " is not within [-1, 1] (the map's linear depth)");
    }
};

namespace detail {
inline float hash_unit(std::uint32_t x) noexcept { // [0, 1), from a 32-bit integer hash
    x ^= x >> 16, x *= 0x7feb352dU, x ^= x >> 15, x *= 0x846ca68bU, x ^= x >> 16;
    return float(x >> 8) * (1.0f / 16777216.0f);
}
} // namespace detail

/// Mix-in giving a shadow map its transmittance queries (CRTP).
template <class Map>
class map_queries {
public:
    /// exp(-optical depth) at texel (x, y) and linear depth.
    float transmittance(int x, int y, float depth) const noexcept { return std::exp(-self().optical_depth(x, y, depth)); }

    /// Transmittance at a world point; 1 outside the map.
    float transmittance(const glm::vec3& world, const query_options& options = {}) const noexcept {
        const light_space& light = self().light();
        const light_point p = light.project(world);
        glm::vec2 window = p.window;
        if (options.jitter) {
            const std::uint32_t h = std::bit_cast<std::uint32_t>(world.x) * 73856093u ^ std::bit_cast<std::uint32_t>(world.y) * 19349663u ^
                                    std::bit_cast<std::uint32_t>(world.z) * 83492791u;
            window += glm::vec2(detail::hash_unit(h) - 0.5f, detail::hash_unit(h ^ 0x9e3779b9u) - 0.5f);
        }
        const int res = light.resolution();
        if (!(p.w > 0.0f) || !(window.x >= 0.0f) || !(window.y >= 0.0f) || !(window.x < float(res)) || !(window.y < float(res)))
            return 1.0f;
        const int x = int(window.x), y = int(window.y);
        const float depth = p.depth - options.depth_bias;
        if (!options.box_filter) return transmittance(x, y, depth);
        float sum = 0.0f;
        int count = 0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= res || ny >= res) continue;
                sum += self().optical_depth(nx, ny, depth);
                ++count;
            }
        return std::exp(-sum / float(count));
    }

    /// Transmittance at many world points, in parallel; out[i] belongs to points[i].
    void transmittance(std::span<const glm::vec3> points, std::span<float> out, const query_options& options = {},
                       const execution& exec = {}) const {
        if (out.size() != points.size()) throw argument_error("output span must match the point count");
        options.check();
        parallel_for(points.size(), exec, [&](std::size_t i) { out[i] = transmittance(points[i], options); }, 4096);
    }

private:
    const Map& self() const noexcept { return static_cast<const Map&>(*this); }
};

} // namespace hairshadow
