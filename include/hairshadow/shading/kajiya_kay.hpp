#pragma once
/// @file
/// Kajiya-Kay hair shading (Kajiya & Kay 1989): a strand is a thin cylinder along its tangent T;
/// diffuse light goes as sin(T, L) and specular light peaks on the cone of directions that mirror
/// L about the strand, as (sin(T, L) sin(T, E) - cos(T, L) cos(T, E))^p with L and E towards the
/// light and the eye. The shadow methods scale each light's contribution by its transmittance.

#include <hairshadow/core/light.hpp>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace hairshadow {

/// How hair reflects light.
struct hair_material {
    glm::vec3 colour{0.50f, 0.33f, 0.20f}; ///< diffuse albedo
    glm::vec3 specular_colour{0.35f, 0.32f, 0.28f};
    float shininess = 40.0f;
    float ambient = 0.12f; ///< unshadowed ambient term, as a fraction of the colour
};

/// Unit direction from `point` towards the light (directional lights: against their direction).
inline glm::vec3 direction_to_light(const light_spec& light, const glm::vec3& point) noexcept {
    const glm::vec3 d = light.type == light_type::directional ? -light.direction : light.position - point;
    const float length = glm::length(d);
    return length > 0.0f ? d / length : glm::vec3(0, 1, 0);
}

/// 1 inside a spot light's cone (and for other lights), 0 outside it.
inline float spot_cone(const light_spec& light, const glm::vec3& point) noexcept {
    if (light.type != light_type::spot) return 1.0f;
    const glm::vec3 d = point - light.position;
    const float length = glm::length(d), axis = glm::length(light.direction);
    if (!(length > 0.0f) || !(axis > 0.0f)) return 0.0f;
    return glm::dot(d, light.direction) / (length * axis) >= std::cos(glm::radians(light.spot_half_angle_degrees)) ? 1.0f : 0.0f;
}

/// Light reflected towards `to_eye` by a strand with unit `tangent` lit from `to_light`, per unit
/// of light colour (diffuse plus specular).
inline glm::vec3 kajiya_kay(const glm::vec3& tangent, const glm::vec3& to_light, const glm::vec3& to_eye, const hair_material& m) noexcept {
    const float tl = glm::dot(tangent, to_light), te = glm::dot(tangent, to_eye);
    const float sin_tl = std::sqrt(std::max(0.0f, 1.0f - tl * tl)), sin_te = std::sqrt(std::max(0.0f, 1.0f - te * te));
    const float cone = std::max(0.0f, sin_tl * sin_te - tl * te);
    return m.colour * sin_tl + m.specular_colour * std::pow(cone, m.shininess);
}

/// Lambert shading of an opaque surface with unit `normal`, per unit of light colour.
inline float lambert(const glm::vec3& normal, const glm::vec3& to_light) noexcept { return std::max(0.0f, glm::dot(normal, to_light)); }

} // namespace hairshadow
