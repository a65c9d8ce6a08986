#pragma once
/// @file
/// The CPU renderer: the opaque mesh by a z-buffered triangle rasteriser with smooth normals and
/// Lambert shading, the hair as anti-aliased lines (coverage of a one-pixel-wide line) with
/// Kajiya-Kay shading computed at the strand points; every light's contribution scaled by the
/// hair's transmittance (any method) and the mesh's depth shadow map, both ways.

#include <hairshadow/core/parallel.hpp>
#include <hairshadow/shading/camera.hpp>
#include <hairshadow/shading/depth_shadow_map.hpp>
#include <hairshadow/shading/image.hpp>
#include <hairshadow/shading/scene.hpp>

#include <algorithm>
#include <functional>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace hairshadow {

/// Transmittance of a light's hair maps at many world points: any method, on either back end.
using transmittance_query = std::function<void(std::span<const glm::vec3> points, std::span<float> out)>;

/// A scene light with its shadows.
struct lit_light {
    scene_light light;
    transmittance_query hair; ///< empty: the hair casts no shadow
    depth_shadow_map mesh;    ///< default: the mesh casts no shadow
};

/// The transmittance query of any map with a batch transmittance(points, out) (CPU methods, the
/// exact map, any_shadow_map).
template <class Map>
transmittance_query query_of(const Map& map, const execution& exec = {}) {
    return [&map, exec](std::span<const glm::vec3> points, std::span<float> out) { map.transmittance(points, out, {}, exec); };
}

struct render_options {
    float line_width = 1.0f; ///< hair lines, in pixels
    bool draw_hair = true;   ///< false: the hair is not drawn but still casts its shadows
    /// Render at this many times the size on each side and average the blocks (1 to 8): smooth edges
    /// of hair and mesh; lines keep their width in output pixels.
    int supersample = 1;
    execution exec;

    /// Throws argument_error for a supersampling factor outside 1..8.
    void check() const {
        if (supersample < 1 || supersample > 8) throw argument_error("render: supersampling must be 1 to 8");
    }
};

/// A light's visibility at `points`: the hair's transmittance times the mesh's depth test (and a
/// spot light's cone).
inline std::vector<float> light_visibility(const lit_light& light, std::span<const glm::vec3> points, const execution& exec = {}) {
    std::vector<float> v(points.size(), 1.0f);
    if (light.hair) light.hair(points, v);
    parallel_for(points.size(), exec, [&](std::size_t i) { v[i] *= light.mesh.visibility(points[i]) * spot_cone(light.light.spec, points[i]); }, 4096);
    return v;
}

namespace detail {

/// Camera-space projection to image coordinates (x right, y down, pixel centres at +0.5) and 1/w.
struct screen_point {
    glm::vec2 xy;
    float inv_w; ///< larger is nearer; interpolates linearly in screen space
    bool valid;
};

inline screen_point to_screen(const glm::mat4& view_projection, const glm::vec3& p, int width, int height) noexcept {
    const glm::vec4 clip = view_projection * glm::vec4(p, 1.0f);
    if (!(clip.w > 1e-6f)) return {{}, 0.0f, false};
    const float inv_w = 1.0f / clip.w;
    return {{(clip.x * inv_w + 1.0f) * 0.5f * float(width), (1.0f - clip.y * inv_w) * 0.5f * float(height)}, inv_w, true};
}

/// What the mesh leaves in each pixel: 1/w (0 where empty), world position and normal.
struct surface_buffer {
    std::vector<float> inv_w;
    std::vector<glm::vec3> position, normal;
};

inline std::vector<glm::vec3> vertex_normals(const triangle_mesh& mesh) {
    std::vector<glm::vec3> n(mesh.vertices.size(), glm::vec3(0.0f));
    for (const auto& t : mesh.triangles) {
        if (t[0] >= n.size() || t[1] >= n.size() || t[2] >= n.size()) continue;
        const glm::vec3 face = glm::cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]);
        for (auto i : t) n[i] += face; // area-weighted
    }
    for (auto& v : n) v = glm::length(v) > 0.0f ? glm::normalize(v) : glm::vec3(0, 1, 0);
    return n;
}

inline surface_buffer rasterise_mesh(const triangle_mesh& mesh, const camera& cam, const execution& exec) {
    const int w = cam.width, h = cam.height;
    surface_buffer s;
    s.inv_w.assign(std::size_t(w) * std::size_t(h), 0.0f);
    s.position.resize(s.inv_w.size());
    s.normal.resize(s.inv_w.size());
    if (mesh.triangles.empty()) return s;
    const glm::mat4 vp = cam.view_projection();
    std::vector<screen_point> screen(mesh.vertices.size());
    for (std::size_t i = 0; i < screen.size(); ++i) screen[i] = to_screen(vp, mesh.vertices[i], w, h);
    const auto normals = vertex_normals(mesh);
    const int bands = (h + scan_band_rows - 1) / scan_band_rows;
    parallel_for(std::size_t(bands), exec, [&](std::size_t band) { // each band owns its pixels
        const int row0 = int(band) * scan_band_rows, row1 = std::min(h, row0 + scan_band_rows);
        const auto window = [&](std::uint32_t i) { return std::pair(screen[i].xy, screen[i].valid); };
        scan_triangles(mesh, row0, row1, w, window, [&](const std::array<std::uint32_t, 3>& t, int x, int row, const glm::vec3& l) {
            const auto &a = screen[t[0]], &b = screen[t[1]], &c = screen[t[2]];
            const float inv_w = l.x * a.inv_w + l.y * b.inv_w + l.z * c.inv_w;
            const std::size_t i = std::size_t(row) * std::size_t(w) + std::size_t(x);
            if (!(inv_w > s.inv_w[i])) return;
            // Perspective-correct weights for the world-space attributes.
            const glm::vec3 q = glm::vec3(l.x * a.inv_w, l.y * b.inv_w, l.z * c.inv_w) / inv_w;
            s.inv_w[i] = inv_w;
            s.position[i] = q.x * mesh.vertices[t[0]] + q.y * mesh.vertices[t[1]] + q.z * mesh.vertices[t[2]];
            s.normal[i] = glm::normalize(q.x * normals[t[0]] + q.y * normals[t[1]] + q.z * normals[t[2]]);
        });
    }, 1);
    return s;
}

/// Unit tangent at each point of each strand (central differences; one-sided at the ends).
inline std::vector<glm::vec3> strand_tangents(const hair_model& hair) {
    std::vector<glm::vec3> t(hair.point_count(), glm::vec3(0, 1, 0));
    for (std::size_t s = 0; s < hair.strand_count(); ++s) {
        const std::size_t first = hair.strand_offsets[s], last = hair.strand_offsets[s + 1];
        for (std::size_t i = first; i < last; ++i) {
            const glm::vec3 d = hair.points[std::min(i + 1, last - 1)] - hair.points[i > first ? i - 1 : i];
            if (glm::length(d) > 0.0f) t[i] = glm::normalize(d);
        }
    }
    return t;
}

/// Calls visit(x, y, depth, coverage, colour) for every pixel each hair line covers in front of the
/// surface, in rows [row0, row1): coverage of a line `line_width` pixels wide, depth as 1/w.
template <class Visit>
void for_each_line_pixel(const hair_model& hair, std::span<const glm::vec3> colours, const camera& cam, const std::vector<float>& surface_inv_w,
                         float line_width, int row0, int row1, const std::vector<screen_point>& screen, Visit&& visit) {
    const float reach = 0.5f * line_width + 0.5f;
    const int w = cam.width;
    for (std::size_t s = 0; s < hair.strand_count(); ++s)
        for (std::uint32_t i = hair.strand_offsets[s]; i + 1 < hair.strand_offsets[s + 1]; ++i) {
            const auto &a = screen[i], &b = screen[i + 1];
            if (!a.valid || !b.valid) continue;
            if (std::max(a.xy.y, b.xy.y) + reach < float(row0) || std::min(a.xy.y, b.xy.y) - reach > float(row1)) continue;
            const glm::vec2 d = b.xy - a.xy;
            const float length2 = glm::dot(d, d);
            const int x0 = floor_index(std::min(a.xy.x, b.xy.x) - reach, 0, w - 1);
            const int x1 = ceil_index(std::max(a.xy.x, b.xy.x) + reach, 0, w - 1);
            const int y0 = floor_index(std::min(a.xy.y, b.xy.y) - reach, row0, row1 - 1);
            const int y1 = ceil_index(std::max(a.xy.y, b.xy.y) + reach, row0, row1 - 1);
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
                    const float t = length2 > 0.0f ? std::clamp(glm::dot(p - a.xy, d) / length2, 0.0f, 1.0f) : 0.0f;
                    const float coverage = std::clamp(reach - glm::length(p - (a.xy + t * d)), 0.0f, 1.0f);
                    if (!(coverage > 0.0f)) continue;
                    const float inv_w = a.inv_w + t * (b.inv_w - a.inv_w);
                    if (!surface_inv_w.empty() && !(inv_w > surface_inv_w[std::size_t(y) * std::size_t(w) + std::size_t(x)])) continue;
                    visit(x, y, inv_w, coverage, colours[i] + t * (colours[i + 1] - colours[i]));
                }
        }
}

} // namespace detail

/// Kajiya-Kay radiance towards the camera at every hair point, each light scaled by its visibility.
inline std::vector<glm::vec3> shade_hair_points(const scene& sc, const camera& cam, std::span<const lit_light> lights, const execution& exec = {}) {
    const auto tangents = detail::strand_tangents(sc.hair);
    std::vector<glm::vec3> colour(sc.hair.point_count(), sc.material.ambient * sc.material.colour);
    for (const auto& light : lights) {
        const auto visible = light_visibility(light, sc.hair.points, exec);
        parallel_for(colour.size(), exec, [&](std::size_t i) {
            const glm::vec3 p = sc.hair.points[i];
            const glm::vec3 to_eye = glm::normalize(cam.eye - p);
            colour[i] += light.light.colour * visible[i] * kajiya_kay(tangents[i], direction_to_light(light.light.spec, p), to_eye, sc.material);
        }, 4096);
    }
    return colour;
}

/// Draws the hair as anti-aliased lines coloured by `point_colours` (one per hair point, linearly
/// interpolated) over `base`, hidden by the mesh's `surface` depths (empty: no mesh). Each pixel
/// shows its nearest well-covered strand, blended by the largest coverage of any strand in front
/// of the mesh: order independent, so identical for any thread count.
/// With `coverage` (one value a pixel), also writes how much of each pixel the hair covers (its
/// largest line coverage; 0 where no hair is drawn).
inline void draw_hair_lines(image& base, const hair_model& hair, std::span<const glm::vec3> point_colours, const camera& cam,
                            const std::vector<float>& surface_inv_w, const render_options& options = {}, std::span<float> coverage = {}) {
    const int w = cam.width, h = cam.height;
    const glm::mat4 vp = cam.view_projection();
    std::vector<detail::screen_point> screen(hair.point_count());
    for (std::size_t i = 0; i < screen.size(); ++i) screen[i] = detail::to_screen(vp, hair.points[i], w, h);
    constexpr int band_rows = 8;
    const int bands = (h + band_rows - 1) / band_rows;
    parallel_for(std::size_t(bands), options.exec, [&](std::size_t band) {
        const int row0 = int(band) * band_rows, row1 = std::min(h, row0 + band_rows);
        const std::size_t n = std::size_t(row1 - row0) * std::size_t(w);
        std::vector<float> full_depth(n, 0.0f), best_coverage(n, 0.0f);
        std::vector<glm::vec3> full_colour(n), best_colour(n);
        std::vector<char> has_full(n, 0);
        detail::for_each_line_pixel(hair, point_colours, cam, surface_inv_w, options.line_width, row0, row1, screen,
                                    [&](int x, int y, float inv_w, float covered, const glm::vec3& c) {
                                        const std::size_t i = std::size_t(y - row0) * std::size_t(w) + std::size_t(x);
                                        if (covered > best_coverage[i]) best_coverage[i] = covered, best_colour[i] = c;
                                        if (covered >= 0.5f && inv_w > full_depth[i]) full_depth[i] = inv_w, full_colour[i] = c, has_full[i] = 1;
                                    });
        for (int y = row0; y < row1; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y - row0) * std::size_t(w) + std::size_t(x);
                if (!coverage.empty()) coverage[std::size_t(y) * std::size_t(w) + std::size_t(x)] = best_coverage[i];
                if (best_coverage[i] > 0.0f) {
                    auto& px = base.at(x, y);
                    px += best_coverage[i] * ((has_full[i] ? full_colour[i] : best_colour[i]) - px);
                }
            }
    });
}

namespace detail {
/// `cam` with `factor` times the pixels on each side, and options whose lines are as wide in the
/// original pixels: what a supersampled render draws.
inline std::pair<camera, render_options> supersampled(const camera& cam, const render_options& options) {
    options.check();
    camera hi = cam;
    hi.width = cam.width * options.supersample;
    hi.height = cam.height * options.supersample;
    camera::check_image_size(hi.width, hi.height);
    render_options o = options;
    o.line_width = options.line_width * float(options.supersample);
    o.supersample = 1;
    return {hi, o};
}
} // namespace detail

/// Renders the scene from `cam` on the CPU; with `coverage` (one value a pixel of the output), also
/// writes how much of each pixel the hair covers (hair_coverage).
inline image render_cpu(const scene& sc, const camera& cam, std::span<const lit_light> lights, const render_options& options = {},
                        std::span<float> coverage = {}) {
    camera::check_image_size(cam.width, cam.height);
    if (!coverage.empty() && coverage.size() != std::size_t(cam.width) * std::size_t(cam.height))
        throw argument_error("render: the coverage needs one value a pixel");
    if (options.supersample != 1) {
        const auto [hi, o] = detail::supersampled(cam, options);
        std::vector<float> hi_coverage(coverage.empty() ? 0 : std::size_t(hi.width) * std::size_t(hi.height));
        const image out = downsample(render_cpu(sc, hi, lights, o, hi_coverage), options.supersample);
        if (!coverage.empty()) { // averaged like the pixels
            const int k = options.supersample;
            std::fill(coverage.begin(), coverage.end(), 0.0f);
            for (int y = 0; y < hi.height; ++y)
                for (int x = 0; x < hi.width; ++x)
                    coverage[std::size_t(y / k) * std::size_t(cam.width) + std::size_t(x / k)] +=
                        hi_coverage[std::size_t(y) * std::size_t(hi.width) + std::size_t(x)] / float(k * k);
        }
        return out;
    }
    image out(cam.width, cam.height, sc.background);
    // The mesh: Lambert shading, each light scaled by the hair's transmittance and the mesh's own shadow.
    const auto surface = detail::rasterise_mesh(sc.mesh, cam, options.exec);
    std::vector<std::size_t> covered;
    for (std::size_t i = 0; i < surface.inv_w.size(); ++i)
        if (surface.inv_w[i] > 0.0f) covered.push_back(i);
    std::vector<glm::vec3> positions(covered.size());
    for (std::size_t k = 0; k < covered.size(); ++k) positions[k] = surface.position[covered[k]];
    std::vector<glm::vec3> radiance(covered.size(), sc.mesh_ambient * sc.mesh_colour);
    for (const auto& light : lights) {
        const auto visible = light_visibility(light, positions, options.exec);
        for (std::size_t k = 0; k < covered.size(); ++k) {
            glm::vec3 n = surface.normal[covered[k]];
            if (glm::dot(n, cam.eye - positions[k]) < 0.0f) n = -n; // two-sided: whichever side faces the camera
            radiance[k] += light.light.colour * sc.mesh_colour * (visible[k] * lambert(n, direction_to_light(light.light.spec, positions[k])));
        }
    }
    for (std::size_t k = 0; k < covered.size(); ++k) out.pixels[covered[k]] = radiance[k];
    // The hair over it.
    if (!coverage.empty()) std::fill(coverage.begin(), coverage.end(), 0.0f);
    if (!options.draw_hair) return out;
    const auto colours = shade_hair_points(sc, cam, lights, options.exec);
    draw_hair_lines(out, sc.hair, colours, cam, surface.inv_w, options, coverage);
    return out;
}

} // namespace hairshadow
