#pragma once
/// @file
/// A perspective camera looking at a scene, and the framing of a bounding box from an orbit angle.

#include <hairshadow/core/bounds.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/config.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <numbers>

namespace hairshadow {

/// A pinhole camera producing a `width` x `height` image.
struct camera {
    glm::vec3 eye{0, 0, 1}, target{0, 0, 0}, up{0, 1, 0};
    float fov_y_degrees = 30.0f;
    int width = 512, height = 512;
    float near_plane = 0.01f, far_plane = 100.0f;

    glm::mat4 view() const { return glm::lookAt(eye, target, up); }
    glm::mat4 projection() const { return glm::perspective(glm::radians(fov_y_degrees), float(width) / float(height), near_plane, far_plane); }
    glm::mat4 view_projection() const { return projection() * view(); }

    /// Orbits `box`: azimuth about +y from +z, elevation above the horizontal plane, at a distance that
    /// fits the box's bounding sphere into the vertical field of view (times `zoom`).
    static camera framing(const aabb& box, float azimuth_degrees, float elevation_degrees, int width, int height, float zoom = 1.0f) {
        if (box.empty()) throw argument_error("camera: nothing to frame");
        check_image_size(width, height);
        if (!(zoom > 0.0f) || !std::isfinite(zoom)) throw argument_error("camera: zoom must be positive");
        if (!std::isfinite(azimuth_degrees) || !std::isfinite(elevation_degrees)) throw argument_error("camera: angles must be finite");
        if (!(std::abs(elevation_degrees) < 89.9f)) throw argument_error("camera: elevation must be within (-89.9, 89.9) degrees");
        camera c;
        c.width = width;
        c.height = height;
        c.target = box.center();
        const float radius = 0.5f * glm::length(box.max - box.min);
        if (!(radius > 0.0f) || !std::isfinite(radius)) throw argument_error("camera: the scene has no extent to frame");
        const float distance = radius / std::sin(glm::radians(0.5f * c.fov_y_degrees)) / zoom;
        const float az = glm::radians(azimuth_degrees), el = glm::radians(elevation_degrees);
        c.eye = c.target + distance * glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
        c.near_plane = std::max(distance - 2.0f * radius, distance * 1e-3f);
        c.far_plane = distance + 2.0f * radius;
        return c;
    }

    /// Throws argument_error unless 1 <= width, height <= HAIRSHADOW_MAX_RESOLUTION.
    static void check_image_size(int width, int height) {
        if (width < 1 || height < 1 || width > HAIRSHADOW_MAX_RESOLUTION || height > HAIRSHADOW_MAX_RESOLUTION)
            throw argument_error("image size must be 1.." + std::to_string(HAIRSHADOW_MAX_RESOLUTION) + " on each side");
    }
};

} // namespace hairshadow
