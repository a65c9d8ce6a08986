#pragma once
/// @file
/// What the renderers draw: hair, an optional opaque mesh, their materials and the lights; and the
/// built-in scenes (a procedural hair on its sphere, a sphere mesh for any model).

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/triangle_mesh.hpp>
#include <hairshadow/shading/kajiya_kay.hpp>

#include <cmath>
#include <numbers>
#include <vector>

namespace hairshadow {

/// A light of the scene and its colour (intensity included).
struct scene_light {
    light_spec spec;
    glm::vec3 colour{1.0f};
};

/// Hair, an opaque mesh (may be empty) and the lights on them.
struct scene {
    hair_model hair;
    triangle_mesh mesh;
    hair_material material;
    glm::vec3 mesh_colour{0.80f, 0.64f, 0.55f};
    float mesh_ambient = 0.15f;
    glm::vec3 background{1.0f, 1.0f, 1.0f};
    std::vector<scene_light> lights;

    /// The box holding the hair and the mesh: what the lights' maps and the camera frame.
    aabb bounds() const {
        aabb box = hair.bounds();
        for (const auto& v : mesh.vertices) box.add(v);
        return box;
    }
};

/// A UV sphere of `rings` latitude bands and 2 x `rings` longitude segments, outward winding.
inline triangle_mesh make_sphere(const glm::vec3& centre, float radius, int rings = 48) {
    if (rings < 2 || rings > 4096) throw argument_error("sphere: rings must be 2..4096");
    if (!(radius > 0.0f) || !std::isfinite(radius)) throw argument_error("sphere: radius must be positive and finite");
    triangle_mesh m;
    const int segments = 2 * rings;
    for (int i = 0; i <= rings; ++i) {
        const float theta = std::numbers::pi_v<float> * float(i) / float(rings);
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * std::numbers::pi_v<float> * float(j) / float(segments);
            m.vertices.push_back(centre + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
        }
    }
    const auto index = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            m.triangles.push_back({index(i, j), index(i, j + 1), index(i + 1, j)});
            m.triangles.push_back({index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)});
        }
    return m;
}

} // namespace hairshadow
