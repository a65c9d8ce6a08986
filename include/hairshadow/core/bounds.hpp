#pragma once
/// @file
/// Axis-aligned bounding box.

#include <glm/vec3.hpp>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <limits>

namespace hairshadow {

/// An axis-aligned box; empty until a point is added.
struct aabb {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    /// Grows the box to hold p.
    void add(const glm::vec3& p) noexcept {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    /// True when no point was added.
    bool empty() const noexcept { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
    glm::vec3 center() const noexcept { return 0.5f * (min + max); }
    glm::vec3 extent() const noexcept { return max - min; }
    /// Length of the diagonal.
    float diagonal() const noexcept { return glm::length(extent()); }
    /// The box grown by `margin` on every side (an empty box stays empty).
    aabb expanded(float margin) const noexcept { return empty() ? *this : aabb{min - glm::vec3(margin), max + glm::vec3(margin)}; }
};

} // namespace hairshadow
