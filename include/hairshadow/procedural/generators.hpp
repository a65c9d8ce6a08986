#pragma once
/// @file
/// Seeded, deterministic procedural hair: straight, wavy, curly and clumped styles grown on a spherical
/// head, and follow-hair that multiplies guide strands (so the Sintel guides can grow into a full head).

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/random.hpp>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace hairshadow {

/// The procedural hair styles.
enum class hair_style { straight, wavy, curly, clumped };

/// Parameters of a procedural model. Units are metres: the head is a sphere of `head_radius` at the
/// origin, y up, like the Sintel model.
struct procedural_options {
    hair_style style = hair_style::straight;
    std::size_t strands = 4000;
    std::size_t segments = 32;        ///< per strand
    std::uint64_t seed = 1;
    float head_radius = 0.1f;
    float length = 0.25f;             ///< strand length
    float wave_amplitude = 0.012f;    ///< wavy: lateral amplitude; curly: helix radius
    float wave_length = 0.06f;        ///< wavy: wavelength; curly: helix pitch
    std::size_t clumps = 200;         ///< clumped: number of clumps
    float clump_strength = 0.85f;     ///< clumped: pull towards the clump's centre at the tip, 0..1
};

/// Most points a generator makes: 2^27, 1.5 GiB of positions: room for a film-scale groom of 100M
/// segments (the streamed exact map's test of scale) and nothing a spec of a few bytes should ask for
/// beyond it (the 1.5M-segment curly model has 1.51M points).
inline constexpr std::size_t max_procedural_points = std::size_t(1) << 27;
/// Most clumps of the clumped style.
inline constexpr std::size_t max_procedural_clumps = 4096;

namespace detail {
inline glm::vec3 any_perpendicular(const glm::vec3& d) {
    const glm::vec3 a = std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::normalize(glm::cross(d, a));
}

/// Root on the upper part of the head (y above -0.25 R, uniform in area) and its outward normal.
inline glm::vec3 sample_root_normal(random_stream& rng) {
    const float y = rng.uniform(-0.25f, 1.0f);
    const float phi = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
    const float r = std::sqrt(std::max(0.0f, 1.0f - y * y));
    return {r * std::cos(phi), y, r * std::sin(phi)};
}

/// A smooth strand that leaves the head along its normal and falls under gravity, kept off the head.
inline std::vector<glm::vec3> grow_centreline(const glm::vec3& normal, const procedural_options& o) {
    std::vector<glm::vec3> pts(o.segments + 1);
    const float step = o.length / float(o.segments);
    glm::vec3 p = normal * o.head_radius;
    const glm::vec3 down(0, -1, 0);
    for (std::size_t i = 0; i <= o.segments; ++i) {
        pts[i] = p;
        const float s = float(i) / float(o.segments);
        glm::vec3 dir = glm::normalize(normal * (1.0f - s) * 1.2f + down * s + glm::vec3(1e-4f, 0, 0));
        p += dir * step;
        const float keep_out = o.head_radius * 1.03f;
        if (glm::length(p) < keep_out) p = glm::normalize(p) * keep_out;
    }
    return pts;
}
} // namespace detail

/// Generates a procedural model; the same options give the same model on every platform.
inline hair_model make_procedural(const procedural_options& o) {
    if (o.strands == 0) throw argument_error("procedural model: strands must be at least 1");
    if (o.segments == 0) throw argument_error("procedural model: segments must be at least 1");
    if (o.segments > 65535) throw argument_error("procedural model: segments per strand must be at most 65535");
    if (o.strands > max_procedural_points / (o.segments + 1))
        throw argument_error("procedural model: strands x (segments + 1) points exceeds " + std::to_string(max_procedural_points));
    if (!(o.head_radius > 0) || !(o.length > 0) || !std::isfinite(o.head_radius) || !std::isfinite(o.length) ||
        !std::isfinite(o.wave_amplitude) || !(o.wave_length > 0) || !std::isfinite(o.wave_length))
        throw argument_error("procedural model: radius, length and wave length must be positive and finite");
    // Each strand looks through every clump: the cap keeps that loop linear in the strands.
    if (o.style == hair_style::clumped && (o.clumps == 0 || o.clumps > o.strands || o.clumps > max_procedural_clumps))
        throw argument_error("procedural model: clumps must be between 1 and the number of strands, at most " +
                             std::to_string(max_procedural_clumps));

    random_stream rng(o.seed);
    std::vector<glm::vec3> clump_normals;
    if (o.style == hair_style::clumped)
        for (std::size_t c = 0; c < o.clumps; ++c) clump_normals.push_back(detail::sample_root_normal(rng));

    hair_model model;
    model.points.reserve(o.strands * (o.segments + 1));
    model.strand_offsets.reserve(o.strands + 1);
    const float two_pi = 2.0f * std::numbers::pi_v<float>;
    for (std::size_t s = 0; s < o.strands; ++s) {
        const glm::vec3 normal = detail::sample_root_normal(rng);
        auto pts = detail::grow_centreline(normal, o);
        const float phase = rng.uniform(0.0f, two_pi);
        const float wave_scale = rng.uniform(0.8f, 1.2f);
        const glm::vec3 side = detail::any_perpendicular(normal);
        switch (o.style) {
        case hair_style::straight: break;
        case hair_style::wavy:
            for (std::size_t i = 1; i < pts.size(); ++i) {
                const float arc = o.length * float(i) / float(o.segments);
                pts[i] += side * (o.wave_amplitude * std::sin(two_pi * arc / (o.wave_length * wave_scale) + phase)) *
                          std::min(1.0f, arc / o.wave_length);
            }
            break;
        case hair_style::curly:
            for (std::size_t i = 1; i < pts.size(); ++i) {
                const glm::vec3 along = glm::normalize(pts[i] - pts[i - 1] + glm::vec3(0, -1e-6f, 0));
                const glm::vec3 u = detail::any_perpendicular(along);
                const glm::vec3 v = glm::cross(along, u);
                const float arc = o.length * float(i) / float(o.segments);
                const float angle = two_pi * arc / (o.wave_length * wave_scale) + phase;
                const float ramp = std::min(1.0f, arc / o.wave_length);
                pts[i] += (u * std::cos(angle) + v * std::sin(angle)) * (o.wave_amplitude * ramp);
            }
            break;
        case hair_style::clumped: {
            // Pull towards the nearest clump centre's strand, more towards the tip.
            std::size_t best = 0;
            for (std::size_t c = 1; c < clump_normals.size(); ++c)
                if (glm::dot(clump_normals[c], normal) > glm::dot(clump_normals[best], normal)) best = c;
            const auto centre = detail::grow_centreline(clump_normals[best], o);
            for (std::size_t i = 1; i < pts.size(); ++i) {
                const float t = o.clump_strength * float(i) / float(o.segments);
                pts[i] = pts[i] * (1.0f - t) + centre[i] * t;
            }
            break;
        }
        }
        model.add_strand(pts);
    }
    model.default_thickness = suggested_thickness(model.bounds());
    try { // extreme shapes (a huge amplitude, say) overflow the points or the bounds: say so here
        validate(model);
    } catch (const model_error& e) {
        throw argument_error(std::string("procedural model: these options give no usable model: ") + e.what());
    }
    if (!(model.default_thickness > 0.0f)) throw argument_error("procedural model: these options give a model with no extent");
    return model;
}

/// Grows `per_guide` strands around each guide (the guide itself first), each offset from its guide by
/// a random vector of length up to `radius` in the plane across the guide's root, and tapering out
/// towards the tip by `tip_spread` (a factor on the offset). Per-point arrays are copied from the guide.
inline hair_model grow_follow_hair(const hair_model& guides, std::size_t per_guide, float radius, std::uint64_t seed = 1,
                                   float tip_spread = 1.5f) {
    if (per_guide == 0) throw argument_error("follow hair: at least 1 strand per guide is needed");
    if (!(radius >= 0) || !std::isfinite(radius) || !std::isfinite(tip_spread)) throw argument_error("follow hair: radius must be finite and >= 0");
    if (guides.point_count() > max_procedural_points / per_guide)
        throw argument_error("follow hair: the result would exceed " + std::to_string(max_procedural_points) + " points");
    hair_model out;
    out.default_thickness = guides.default_thickness;
    out.default_transparency = guides.default_transparency;
    out.default_color = guides.default_color;
    out.points.reserve(guides.point_count() * per_guide);
    random_stream rng(seed);
    for (std::size_t g = 0; g < guides.strand_count(); ++g) {
        const auto guide = guides.strand(g);
        const std::size_t first = guides.strand_offsets[g];
        glm::vec3 root_dir = guide.size() > 1 ? guide[1] - guide[0] : glm::vec3(0, -1, 0);
        root_dir = glm::length(root_dir) > 0 ? glm::normalize(root_dir) : glm::vec3(0, -1, 0);
        const glm::vec3 u = detail::any_perpendicular(root_dir);
        const glm::vec3 v = glm::cross(root_dir, u);
        for (std::size_t k = 0; k < per_guide; ++k) {
            glm::vec3 offset(0);
            if (k > 0) {
                const float r = radius * std::sqrt(rng.uniform());
                const float a = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
                offset = (u * std::cos(a) + v * std::sin(a)) * r;
            }
            const std::size_t n = guide.size();
            for (std::size_t i = 0; i < n; ++i) {
                const float t = n > 1 ? float(i) / float(n - 1) : 0.0f;
                out.points.push_back(guide[i] + offset * (1.0f + (tip_spread - 1.0f) * t));
            }
            out.strand_offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
            auto copy = [&](const auto& src, auto& dst) {
                if (!src.empty()) dst.insert(dst.end(), src.begin() + std::ptrdiff_t(first), src.begin() + std::ptrdiff_t(first + n));
            };
            copy(guides.thickness, out.thickness);
            copy(guides.transparency, out.transparency);
            copy(guides.colors, out.colors);
        }
    }
    try {
        validate(out);
    } catch (const model_error& e) {
        throw argument_error(std::string("follow hair: these options give no usable model: ") + e.what());
    }
    return out;
}

} // namespace hairshadow
