#pragma once
/// @file
/// A conventional depth shadow map of an opaque triangle mesh (Williams 1978), in the same light
/// space as the hair's maps, so that the two combine both ways (Yuksel & Keyser 2008, Fig. 7;
/// Sintorn & Assarsson 2009, section 3.5): the mesh receives the hair's transmittance, and hair behind
/// the mesh from the light is fully shadowed.

#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/core/triangle_mesh.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>
#include <utility>
#include <vector>

namespace hairshadow {

namespace detail {
/// floor(v) and ceil(v) as pixel indices clamped to [lo, hi] before the conversion (window
/// coordinates of points near the eye or light plane can be beyond int's range); NaN gives lo.
inline int floor_index(float v, int lo, int hi) noexcept { return v > float(lo) ? int(std::min(std::floor(v), float(hi))) : lo; }
inline int ceil_index(float v, int lo, int hi) noexcept { return v > float(lo) ? int(std::min(std::ceil(v), float(hi))) : lo; }

inline float edge_function(const glm::vec2& a, const glm::vec2& b, const glm::vec2& p) noexcept {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

/// Calls visit(triangle, x, row, barycentrics) for every pixel centre of rows [row0, row1) (of
/// `width` pixels) inside a triangle of `mesh` whose three vertices are valid: `window(i)` gives
/// vertex i's pixel coordinates and whether it is in front of the eye. Each triangle is set up once
/// for the rows it spans; triangles are visited in mesh order, so a pixel sees them in that order.
template <class Window, class Visit>
void scan_triangles(const triangle_mesh& mesh, int row0, int row1, int width, Window&& window, Visit&& visit) {
    const std::size_t n = mesh.vertices.size();
    for (const auto& t : mesh.triangles) {
        if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
        const auto [a, a_ok] = window(t[0]);
        const auto [b, b_ok] = window(t[1]);
        const auto [c, c_ok] = window(t[2]);
        if (!a_ok || !b_ok || !c_ok) continue; // no near-plane clipping: such triangles are dropped
        // Rows whose centre y + 0.5 lies within the triangle's vertical extent.
        const int first = std::max(row0, ceil_index(std::min({a.y, b.y, c.y}) - 0.5f, row0, row1));
        const int last = std::min(row1 - 1, floor_index(std::max({a.y, b.y, c.y}) - 0.5f, row0 - 1, row1 - 1));
        if (first > last) continue;
        const float area = edge_function(a, b, c);
        if (!(std::abs(area) > 0.0f)) continue;
        const int x0 = floor_index(std::min({a.x, b.x, c.x}), 0, width - 1), x1 = ceil_index(std::max({a.x, b.x, c.x}), 0, width - 1);
        for (int row = first; row <= last; ++row)
            for (int x = x0; x <= x1; ++x) {
                const glm::vec2 p(float(x) + 0.5f, float(row) + 0.5f);
                const glm::vec3 l(edge_function(b, c, p) / area, edge_function(c, a, p) / area, edge_function(a, b, p) / area);
                if (l.x < 0.0f || l.y < 0.0f || l.z < 0.0f) continue;
                visit(t, x, row, l);
            }
    }
}

/// Rows per parallel task of the triangle scans.
inline constexpr int scan_band_rows = 8;
} // namespace detail

/// Bias of the mesh's depth comparisons, in linear depth units (of the light's near-far range):
/// enough to keep a surface lit by its own map on the Sintel head at 512x512.
inline constexpr float default_mesh_bias = 6e-3f;

/// Nearest opaque depth per texel of a light's map.
class depth_shadow_map {
public:
    depth_shadow_map() = default;

    /// Rasterises `mesh` from `light` (texel centres inside a triangle, as GL's rule for polygons).
    /// `bias` is added to the stored depth before comparisons, in linear depth units.
    depth_shadow_map(const triangle_mesh& mesh, const light_space& light, float bias = default_mesh_bias, const execution& exec = {})
        : light_(light), bias_(bias) {
        const int res = light.resolution();
        depth_.assign(std::size_t(res) * std::size_t(res), std::numeric_limits<float>::infinity());
        if (mesh.triangles.empty()) return;
        struct projected {
            glm::vec2 window;
            float depth_over_w, one_over_w; // perspective-correct interpolation of linear depth
            bool valid;
        };
        std::vector<projected> points(mesh.vertices.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
            const auto p = light.project(mesh.vertices[i]);
            points[i] = {p.window, p.depth / p.w, 1.0f / p.w, p.w > 0.0f};
        }
        // Bands of rows in parallel: each band owns its texels, so the result is the same for any thread count.
        const int bands = (res + detail::scan_band_rows - 1) / detail::scan_band_rows;
        parallel_for(std::size_t(bands), exec, [&](std::size_t band) {
            const int row0 = int(band) * detail::scan_band_rows, row1 = std::min(res, row0 + detail::scan_band_rows);
            const auto window = [&](std::uint32_t i) { return std::pair(points[i].window, points[i].valid); };
            detail::scan_triangles(mesh, row0, row1, res, window, [&](const std::array<std::uint32_t, 3>& t, int x, int row, const glm::vec3& l) {
                const auto &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
                float& stored = depth_[std::size_t(row) * std::size_t(res) + std::size_t(x)];
                const float depth = (l.x * a.depth_over_w + l.y * b.depth_over_w + l.z * c.depth_over_w) /
                                    (l.x * a.one_over_w + l.y * b.one_over_w + l.z * c.one_over_w);
                stored = std::min(stored, depth);
            });
        }, 1);
    }

    /// 1 where `world` is in front of the mesh from the light (or outside the map), else 0.
    float visibility(const glm::vec3& world) const noexcept {
        if (depth_.empty()) return 1.0f;
        const auto t = light_.locate(world);
        if (!t) return 1.0f;
        return t->depth <= depth(t->x, t->y) + bias_ ? 1.0f : 0.0f;
    }

    /// Stored depth of texel (x, y); infinity where no triangle covers it.
    float depth(int x, int y) const noexcept { return depth_[std::size_t(y) * std::size_t(light_.resolution()) + std::size_t(x)]; }
    const light_space& light() const noexcept { return light_; }

private:
    light_space light_;
    float bias_ = 0.0f;
    std::vector<float> depth_;
};

} // namespace hairshadow
