#pragma once
/// @file
/// Lights and the light space of a shadow map: a directional light gets an orthographic frustum fitted
/// to the model's bounds; point and spot lights get a perspective one. Maps world points to
/// (texel, depth), where depth is the linear distance from the light's near plane, normalised to [0, 1].

#include <hairshadow/config.hpp>
#include <hairshadow/core/bounds.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/parse.hpp>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <optional>
#include <string>

namespace hairshadow {

/// Kinds of light.
enum class light_type { directional, point, spot };

/// A light: a directional light travels along `direction`; point and spot lights sit at `position`;
/// a spot light looks along `direction` with a cone of half-angle `spot_half_angle_degrees`.
struct light_spec {
    light_type type = light_type::directional;
    glm::vec3 direction{0, -1, 0};
    glm::vec3 position{0};
    float spot_half_angle_degrees = 30.0f;

    static light_spec directional(const glm::vec3& dir) { return {light_type::directional, dir, glm::vec3(0), 0.0f}; }
    static light_spec point(const glm::vec3& pos) { return {light_type::point, glm::vec3(0, -1, 0), pos, 0.0f}; }
    static light_spec spot(const glm::vec3& pos, const glm::vec3& dir, float half_angle_degrees) {
        return {light_type::spot, dir, pos, half_angle_degrees};
    }
};

/// The grammar of light specs.
inline constexpr std::string_view light_grammar = "dir:X,Y,Z | point:X,Y,Z | spot:X,Y,Z:DX,DY,DZ:HALF_ANGLE_DEGREES";

namespace detail {
inline glm::vec3 parse_vec3(std::string_view text, std::string_view what) {
    const auto parts = split(text, ',');
    if (parts.size() != 3) throw argument_error(std::string(what) + ": expected three comma-separated numbers, got '" + std::string(text) + "'");
    return {parse_number<float>(parts[0], what), parse_number<float>(parts[1], what), parse_number<float>(parts[2], what)};
}
} // namespace detail

/// Throws argument_error for what is wrong with a light on its own, whatever the model: a zero or
/// non-finite direction, a non-finite position, a spot half-angle outside (0, 89) degrees.
inline void check_light_spec(const light_spec& light) {
    const auto finite3 = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (light.type != light_type::point && (!finite3(light.direction) || light.direction == glm::vec3(0.0f)))
        throw argument_error("the light direction is zero or not finite");
    if (light.type != light_type::directional && !finite3(light.position)) throw argument_error("the light position is not finite");
    if (light.type == light_type::spot && !(light.spot_half_angle_degrees > 0.0f && light.spot_half_angle_degrees < 89.0f))
        throw argument_error("the spot light half-angle must be in (0, 89) degrees");
}

/// Parses `dir:x,y,z` (the direction the light travels), `point:x,y,z` or `spot:x,y,z:dx,dy,dz:angle`,
/// and checks the result with check_light_spec.
inline light_spec parse_light_spec(std::string_view spec) {
    try {
        const auto parts = detail::split(spec, ':');
        std::optional<light_spec> light;
        if (parts[0] == "dir" && parts.size() == 2) light = light_spec::directional(detail::parse_vec3(parts[1], "light direction"));
        if (parts[0] == "point" && parts.size() == 2) light = light_spec::point(detail::parse_vec3(parts[1], "light position"));
        if (parts[0] == "spot" && parts.size() == 4)
            light = light_spec::spot(detail::parse_vec3(parts[1], "light position"), detail::parse_vec3(parts[2], "light direction"),
                                     detail::parse_number<float>(parts[3], "spot angle"));
        if (light) {
            check_light_spec(*light);
            return *light;
        }
    } catch (const argument_error& e) {
        throw argument_error("bad light spec '" + std::string(spec) + "': " + e.what() + "; expected " + std::string(light_grammar));
    }
    throw argument_error("bad light spec '" + std::string(spec) + "'; expected " + std::string(light_grammar));
}

/// Farthest a point or spot light may be from the model's centre, in radii of its bounding sphere:
/// farther, the model's depth span is a few float steps of the distance (use a directional light).
inline constexpr float max_light_distance_in_radii = 1.0e4f;

namespace detail {
/// `v` scaled to unit length; scaled down first, so that a huge direction does not overflow.
inline glm::vec3 unit_direction(const glm::vec3& v, const char* what) {
    const float largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!std::isfinite(largest) || !(largest > 0.0f)) throw argument_error(std::string(what) + " is zero or not finite");
    const glm::vec3 unit = glm::normalize(v / largest);
    if (!(std::isfinite(unit.x) && std::isfinite(unit.y) && std::isfinite(unit.z))) throw argument_error(std::string(what) + " is not usable");
    return unit;
}
} // namespace detail

/// Throws argument_error unless 1 <= resolution <= HAIRSHADOW_MAX_RESOLUTION.
inline void check_resolution(long long resolution) {
    if (resolution < 1 || resolution > HAIRSHADOW_MAX_RESOLUTION)
        throw argument_error("resolution " + std::to_string(resolution) + " is outside 1.." + std::to_string(HAIRSHADOW_MAX_RESOLUTION));
}


/// A world point seen from the light: window coordinates in texels, linear depth in [0, 1] inside the
/// frustum, and the clip-space w (1 for orthographic lights).
struct light_point {
    glm::vec2 window;
    float depth;
    float w;
};

/// The texel a world point falls in, and its depth; see light_space::locate.
struct texel_depth {
    int x, y;
    float depth;
};

/// Everything a light_space holds, as a file stores it (io/deep_exr.hpp): light_space::parts() and
/// light_space::from_parts() give the same light back, bit for bit.
struct light_space_parts {
    int resolution = 1;
    light_type type = light_type::directional;
    glm::mat4 view{1.0f}, projection{1.0f}, view_projection{1.0f};
    float near_plane = 0.0f, far_plane = 1.0f;
    float half_extent = 1.0f;

    /// The same light, member by member (what a file must hold to map points as the light did).
    bool operator==(const light_space_parts&) const = default;
};

/// The frustum and resolution of one shadow map.
class light_space {
public:
    /// Fits the light's frustum to `bounds` at `resolution` texels per side. Throws argument_error for a
    /// zero or non-finite direction, an out-of-range resolution, or a point light inside the bounds.
    HAIRSHADOW_DECL static light_space fit(const light_spec& light, const aabb& bounds, int resolution);

    /// The light stored elsewhere (a file's header). Throws argument_error for an out-of-range
    /// resolution, a non-finite matrix, near >= far or a non-positive or non-finite half extent.
    static light_space from_parts(const light_space_parts& p) {
        check_resolution(p.resolution);
        if (p.type != light_type::directional && p.type != light_type::point && p.type != light_type::spot) throw argument_error("unknown light type");
        for (const glm::mat4* m : {&p.view, &p.projection, &p.view_projection})
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    if (!std::isfinite((*m)[c][r])) throw argument_error("the light's matrices are not finite");
        if (!std::isfinite(p.near_plane) || !std::isfinite(p.far_plane) || !(p.far_plane > p.near_plane))
            throw argument_error("the light's near and far planes are not finite, increasing distances");
        if (!(p.half_extent > 0.0f) || !std::isfinite(p.half_extent)) throw argument_error("the light's half extent is not positive and finite");
        light_space ls;
        ls.resolution_ = p.resolution, ls.type_ = p.type;
        ls.view_ = p.view, ls.projection_ = p.projection, ls.view_projection_ = p.view_projection;
        ls.near_ = p.near_plane, ls.far_ = p.far_plane, ls.half_extent_ = p.half_extent;
        return ls;
    }
    light_space_parts parts() const noexcept { return {resolution_, type_, view_, projection_, view_projection_, near_, far_, half_extent_}; }

    int resolution() const noexcept { return resolution_; }
    light_type type() const noexcept { return type_; }
    bool perspective() const noexcept { return type_ != light_type::directional; }
    const glm::mat4& view() const noexcept { return view_; }
    const glm::mat4& projection() const noexcept { return projection_; }
    const glm::mat4& view_projection() const noexcept { return view_projection_; }
    /// Distances of the near and far planes from the light, in world units.
    float near_plane() const noexcept { return near_; }
    float far_plane() const noexcept { return far_; }

    /// Linear depth in [0, 1] of a view-space distance from the light.
    float depth_of_distance(float distance) const noexcept { return (distance - near_) / (far_ - near_); }
    /// Distance from the light of a linear depth.
    float distance_of_depth(float depth) const noexcept { return near_ + depth * (far_ - near_); }

    /// Projects a world point (no clipping): window coordinates, linear depth and clip w.
    HAIRSHADOW_ALWAYS_INLINE light_point project(const glm::vec3& world) const noexcept { return project(world, distance_of(world)); }
    /// The same, given the point's distance_of(world).
    HAIRSHADOW_ALWAYS_INLINE light_point project(const glm::vec3& world, float distance) const noexcept {
        const float x = row(view_projection_, 0, world), y = row(view_projection_, 1, world), w = row(view_projection_, 3, world);
        const float half_res = 0.5f * float(resolution_);
        return {glm::vec2((x / w + 1.0f) * half_res, (y / w + 1.0f) * half_res), depth_of_distance(distance), w};
    }
    /// Distance of a world point in front of the light, along its axis (view space -z).
    HAIRSHADOW_ALWAYS_INLINE float distance_of(const glm::vec3& world) const noexcept { return -row(view_, 2, world); }

    /// The texel holding a world point and its depth, or nothing when the point is outside the map.
    std::optional<texel_depth> locate(const glm::vec3& world) const noexcept {
        const light_point p = project(world);
        if (!(p.w > 0.0f) || !(p.window.x >= 0.0f) || !(p.window.y >= 0.0f) || !(p.window.x < float(resolution_)) ||
            !(p.window.y < float(resolution_)))
            return std::nullopt;
        return texel_depth{int(p.window.x), int(p.window.y), p.depth};
    }

    /// Half the map's width: in world units for a directional light, else the tangent of the half-angle.
    float half_extent() const noexcept { return half_extent_; }
    /// World-space width of one texel at a linear depth (constant for a directional light).
    float texel_size(float depth) const noexcept {
        if (!perspective()) return 2.0f * half_extent_ / float(resolution_);
        return 2.0f * half_extent_ * distance_of_depth(depth) / float(resolution_);
    }

private:
    /// Row i of m * (p, 1), summed in the order of GLM's matrix-vector product, inlined: the
    /// rasteriser projects every point of the model. Every product is rounded before it is summed,
    /// as the vector projection of the tiled build rounds it (detail::rounded).
    HAIRSHADOW_ALWAYS_INLINE static float row(const glm::mat4& m, int i, const glm::vec3& p) noexcept {
        using detail::rounded;
        return (rounded(m[0][i] * p.x) + rounded(m[1][i] * p.y)) + (rounded(m[2][i] * p.z) + m[3][i]);
    }

public:
    /// The coefficients of row(view_projection(), i) for i = 0, 1, 3 and of row(view(), 2), for the
    /// vector projection: {m[0][i], m[1][i], m[2][i], m[3][i]}.
    std::array<float, 4> row_coefficients(const glm::mat4& m, int i) const noexcept { return {m[0][i], m[1][i], m[2][i], m[3][i]}; }

private:

    int resolution_ = 1;
    light_type type_ = light_type::directional;
    glm::mat4 view_{1.0f}, projection_{1.0f}, view_projection_{1.0f};
    float near_ = 0.0f, far_ = 1.0f;
    float half_extent_ = 1.0f; ///< orthographic half width, or tan of the perspective half-angle
};

#if HAIRSHADOW_KERNEL_BODIES
HAIRSHADOW_DECL light_space light_space::fit(const light_spec& light, const aabb& bounds, int resolution) {
    check_resolution(resolution);
    check_light_spec(light);
    if (bounds.empty() || !std::isfinite(bounds.diagonal())) throw argument_error("the model's bounds are empty or not finite");
    light_space ls;
    ls.resolution_ = resolution;
    ls.type_ = light.type;
    const glm::vec3 center = bounds.center();
    const float radius = std::max(0.5f * bounds.diagonal(), 1e-6f);
    // World coordinates are floats: a model far from the origin for its size has too few steps
    // of its own coordinates to be told apart in depth.
    const float offset = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
    if (!(offset <= max_light_distance_in_radii * radius))
        throw argument_error("the model lies more than " + std::to_string(int(max_light_distance_in_radii)) +
                             " radii from the origin, too far for float coordinates; move it nearer the origin");
    glm::vec3 forward;
    glm::vec3 eye;
    if (light.type == light_type::directional) {
        forward = detail::unit_direction(light.direction, "the light direction");
        eye = center - forward * (2.0f * radius);
    } else {
        eye = light.position;
        // Depth is a float distance from the light: from too far away, the model's whole depth
        // span falls within a few of its steps (and the frustum's products overflow).
        const double distance = glm::length(glm::dvec3(center) - glm::dvec3(eye));
        if (!(distance <= double(max_light_distance_in_radii) * double(radius)))
            throw argument_error("the light is more than " + std::to_string(int(max_light_distance_in_radii)) +
                                 " model radii away, too far for float depth; use a directional light (dir:X,Y,Z)");
        if (light.type == light_type::spot) {
            forward = detail::unit_direction(light.direction, "the spot light direction");
        } else {
            if (glm::length(center - eye) <= radius * 1.0001f)
                throw argument_error("the point light is inside the model's bounding sphere; a single perspective map cannot cover it");
            forward = glm::normalize(center - eye);
        }
    }
    const glm::vec3 up = std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    ls.view_ = glm::lookAt(eye, eye + forward, up);

    // Extent of the bounds' corners in view space.
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? bounds.max.x : bounds.min.x, (c & 2) ? bounds.max.y : bounds.min.y,
                               (c & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 v = glm::vec3(ls.view_ * glm::vec4(corner, 1.0f));
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const float dmin = -hi.z, dmax = -lo.z; // distances in front of the light
    const float margin = std::max(0.01f * (dmax - dmin), 1e-4f * radius);
    if (light.type == light_type::directional) {
        // Square texels; half a percent of padding keeps every point strictly inside the map.
        const float half = 0.5f * std::max(hi.x - lo.x, hi.y - lo.y) * 1.01f + 1e-6f * radius;
        const float cx = 0.5f * (lo.x + hi.x), cy = 0.5f * (lo.y + hi.y);
        ls.near_ = dmin - margin;
        ls.far_ = dmax + margin;
        ls.half_extent_ = half;
        ls.projection_ = glm::ortho(cx - half, cx + half, cy - half, cy + half, ls.near_, ls.far_);
    } else {
        float half_tan;
        if (light.type == light_type::point) {
            const float dist = glm::length(center - eye);
            half_tan = std::tan(std::asin(std::min(radius / dist, 0.999f))) * 1.01f;
            ls.near_ = std::max(dist - radius, dist * 1e-3f) * 0.99f;
            ls.far_ = (dist + radius) * 1.01f;
        } else {
            half_tan = std::tan(glm::radians(light.spot_half_angle_degrees));
            if (dmax <= 0.0f) throw argument_error("the model lies behind the spot light");
            ls.near_ = std::max(dmin - margin, std::max(dmax, 1e-6f) * 1e-3f);
            ls.far_ = dmax + margin;
        }
        ls.half_extent_ = half_tan;
        ls.projection_ = glm::frustum(-half_tan * ls.near_, half_tan * ls.near_, -half_tan * ls.near_, half_tan * ls.near_,
                                      ls.near_, ls.far_);
    }
    ls.view_projection_ = ls.projection_ * ls.view_;
    const auto finite_matrix = [](const glm::mat4& m) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) return false;
        return true;
    };
    if (!finite_matrix(ls.view_projection_) || !std::isfinite(ls.near_) || !std::isfinite(ls.far_) || !(ls.far_ > ls.near_) ||
        !(ls.half_extent_ > 0.0f) || !std::isfinite(ls.half_extent_))
        throw argument_error("the light and the model's bounds give no usable frustum (too far apart, or too large for float)");
    return ls;
}
#endif

} // namespace hairshadow
