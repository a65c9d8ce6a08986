#pragma once
/// @file
/// An opaque triangle mesh (a head or body that receives and casts shadows).

#include <hairshadow/core/bounds.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace hairshadow {

/// Indexed triangles.
struct triangle_mesh {
    std::vector<glm::vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;

    aabb bounds() const noexcept {
        aabb box;
        for (const auto& v : vertices) box.add(v);
        return box;
    }
};

} // namespace hairshadow
