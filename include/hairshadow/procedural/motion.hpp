#pragma once
/// @file
/// Seeded procedural motion for any hair model, to rebuild maps frame after frame as a renderer does:
/// wind sway (roots fixed, every segment's length kept) and a light that orbits the model.

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/core/random.hpp>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

namespace hairshadow {

/// Parameters of wind sway. Each strand bends as a whole: segment j turns about the axis wind x up by
/// the tip's angle times the fraction of the strand's points before it, so a strand curves more
/// towards its tip, as hair does, while its root and every segment's length stay as they were.
struct sway_options {
    glm::vec3 wind{1.0f, 0.0f, 0.0f}; ///< the direction the hair swings along (not parallel to `up`)
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float amplitude_degrees = 14.0f;  ///< the tip's largest turn from rest, either way
    float period = 2.0f;              ///< seconds per swing
    /// World units a gust travels along the wind in one period: strands closer than this along the
    /// wind sway nearly together, as neighbouring hair does.
    float gust_length = 0.6f;
    float strand_variation = 0.15f;   ///< each strand's own phase offset, at most this fraction of a period
    std::uint64_t seed = 1;

    /// Throws argument_error for a value no sway can use: non-finite, a zero or non-finite wind or up,
    /// wind parallel to up, a period or gust length that is not positive, an amplitude above 90 degrees,
    /// or a variation outside [0, 1].
    void check() const {
        const auto finite3 = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
        if (!finite3(wind) || !finite3(up) || glm::length(wind) == 0.0f || glm::length(up) == 0.0f)
            throw argument_error("sway: wind and up must be finite, non-zero directions");
        if (!(glm::length(glm::cross(glm::normalize(wind), glm::normalize(up))) > 1e-3f))
            throw argument_error("sway: the wind must not be parallel to up");
        if (!(amplitude_degrees >= 0.0f && amplitude_degrees <= 90.0f))
            throw argument_error("sway: the amplitude must be 0 to 90 degrees, not " + std::to_string(amplitude_degrees));
        if (!(period > 0.0f) || !std::isfinite(period)) throw argument_error("sway: the period must be positive and finite");
        if (!(gust_length > 0.0f) || !std::isfinite(gust_length)) throw argument_error("sway: the gust length must be positive and finite");
        if (!(strand_variation >= 0.0f && strand_variation <= 1.0f)) throw argument_error("sway: the strand variation must be 0 to 1");
    }
};

/// Wind sway of a model at rest: pose(t, out) writes the model at time t. The same for a seed and any
/// thread count (each strand is posed on its own; across compilers and C libraries, sin and cos may
/// differ in the last bit); a pose into a model of the rest's shape allocates nothing.
class sway_motion {
public:
    explicit sway_motion(hair_model rest, const sway_options& options = {}) : rest_(std::move(rest)), options_(options) {
        options_.check();
        validate(rest_);
        wind_ = glm::normalize(options_.wind);
        axis_ = glm::normalize(glm::cross(wind_, glm::normalize(options_.up)));
    }

    const hair_model& rest() const noexcept { return rest_; }
    const sway_options& options() const noexcept { return options_; }

    /// The tip's turn of strand s at time t, in radians.
    float tip_angle(std::size_t s, float t) const noexcept {
        constexpr float two_pi = 2.0f * std::numbers::pi_v<float>;
        const glm::vec3& root = rest_.points[rest_.strand_offsets[s]];
        random_stream stream(options_.seed * 0x9E3779B97F4A7C15ull + s);
        // The time within its period first, so that a clock that has run for hours keeps its precision.
        const float cycle = float(std::fmod(double(t), double(options_.period)) / double(options_.period));
        const float phase = two_pi * (cycle - glm::dot(root, wind_) / options_.gust_length + options_.strand_variation * stream.uniform());
        // A swing and a smaller, faster flutter: the hair does not return along the path it took.
        const float swing = 0.8f * std::sin(phase) + 0.2f * std::sin(2.0f * phase + 1.0f);
        return options_.amplitude_degrees * (std::numbers::pi_v<float> / 180.0f) * swing;
    }

    /// Writes the hair at time `t` (seconds) into `out`: the rest model with its points moved. `out`
    /// takes the rest's strands, thickness, transparency and colour if its shape differs; otherwise
    /// only its points are written, in place.
    void pose(float t, hair_model& out, const execution& exec = {}) const {
        if (!std::isfinite(t)) throw argument_error("sway: the time must be finite");
        if (out.strand_offsets != rest_.strand_offsets || out.points.size() != rest_.points.size()) out = rest_;
        parallel_for(rest_.strand_count(), exec, [&](std::size_t s) {
            const std::uint32_t first = rest_.strand_offsets[s], end = rest_.strand_offsets[s + 1];
            if (end - first < 2) { // a lone point (or none) stays where it is
                if (end > first) out.points[first] = rest_.points[first];
                return;
            }
            const float tip = tip_angle(s, t);
            const float last = float(end - first - 1);
            glm::vec3 p = rest_.points[first];
            out.points[first] = p;
            for (std::uint32_t i = first; i + 1 < end; ++i) {
                const float angle = tip * float(i + 1 - first) / last;
                p += rotated(rest_.points[i + 1] - rest_.points[i], angle);
                out.points[i + 1] = p;
            }
        }, 64);
    }

    /// The model at time `t`.
    hair_model pose(float t, const execution& exec = {}) const {
        hair_model out = rest_;
        pose(t, out, exec);
        return out;
    }

private:
    /// v turned by `angle` about axis_ (Rodrigues' formula).
    glm::vec3 rotated(const glm::vec3& v, float angle) const noexcept {
        const float c = std::cos(angle), s = std::sin(angle);
        return v * c + glm::cross(axis_, v) * s + axis_ * glm::dot(axis_, v) * (1.0f - c);
    }

    hair_model rest_;
    sway_options options_;
    glm::vec3 wind_{}, axis_{};
};

/// `light` turned about the vertical line through `centre` by a full turn every `period` seconds, at
/// time `t`: its direction, and for point and spot lights its position. A light straight above or
/// below stays where it is.
inline light_spec orbit_light(const light_spec& light, float t, float period, const glm::vec3& centre = glm::vec3(0.0f)) {
    if (!std::isfinite(t) || !(period > 0.0f) || !std::isfinite(period)) throw argument_error("orbit: the time and a positive period must be finite");
    const float angle = 2.0f * std::numbers::pi_v<float> * std::fmod(t / period, 1.0f);
    const float c = std::cos(angle), s = std::sin(angle);
    const auto turn = [&](const glm::vec3& v) { return glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); };
    light_spec out = light;
    out.direction = turn(light.direction);
    out.position = centre + turn(light.position - centre);
    return out;
}

} // namespace hairshadow
