#pragma once
/// @file
/// The hair model: strands of points with optional per-point thickness, transparency and colour.

#include <hairshadow/config.hpp>
#include <hairshadow/core/bounds.hpp>
#include <hairshadow/core/error.hpp>

#include <glm/vec3.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace hairshadow {

/// Strands of points. Strand i holds points [strand_offsets[i], strand_offsets[i + 1]).
/// The optional per-point arrays are either empty (the default applies to every point) or hold one
/// value per point.
struct hair_model {
    std::vector<glm::vec3> points;
    std::vector<std::uint32_t> strand_offsets{0};
    std::vector<float> thickness;     ///< strand diameter per point, in model units
    std::vector<float> transparency;  ///< per point, 0 = opaque, 1 = invisible
    std::vector<glm::vec3> colors;    ///< per point, linear RGB

    float default_thickness = 0.0f;   ///< used when thickness is empty; 0 = not given by the source
    float default_transparency = 0.0f;
    glm::vec3 default_color{0.4f, 0.3f, 0.2f};

    std::size_t strand_count() const noexcept { return strand_offsets.size() - 1; }
    std::size_t point_count() const noexcept { return points.size(); }
    /// Number of points of strand s.
    std::size_t strand_size(std::size_t s) const noexcept { return strand_offsets[s + 1] - strand_offsets[s]; }
    /// Segments over all strands: a strand of n points has n - 1 (none when n < 2).
    std::size_t segment_count() const noexcept {
        std::size_t n = 0;
        for (std::size_t s = 0; s < strand_count(); ++s) n += strand_size(s) > 0 ? strand_size(s) - 1 : 0;
        return n;
    }
    /// The points of strand s.
    std::span<const glm::vec3> strand(std::size_t s) const noexcept {
        return {points.data() + strand_offsets[s], strand_size(s)};
    }
    /// Appends a strand; the per-point arrays, when present, must be appended by the caller.
    void add_strand(std::span<const glm::vec3> strand_points) {
        if (strand_points.size() > std::numeric_limits<std::uint32_t>::max() - points.size())
            throw model_error("more than 2^32 points");
        points.insert(points.end(), strand_points.begin(), strand_points.end());
        strand_offsets.push_back(static_cast<std::uint32_t>(points.size()));
    }

    float thickness_at(std::size_t point) const noexcept {
        return thickness.empty() ? default_thickness : thickness[point];
    }
    float transparency_at(std::size_t point) const noexcept {
        return transparency.empty() ? default_transparency : transparency[point];
    }
    glm::vec3 color_at(std::size_t point) const noexcept { return colors.empty() ? default_color : colors[point]; }

    /// Bounds of all points.
    aabb bounds() const noexcept {
        aabb box;
        for (const auto& p : points) box.add(p);
        return box;
    }
};

/// The thickness used when a model gives none: 1/5000 of its bounding-box diagonal, which is a
/// human hair's 70-90 micrometres on a 0.4-0.5 m head of hair (a documented choice, not a paper's).
inline float suggested_thickness(const aabb& box) noexcept { return box.diagonal() / 5000.0f; }

/// Fills default_thickness from the bounds when neither per-point nor default thickness is given.
inline void ensure_thickness(hair_model& model) {
    if (model.thickness.empty() && !(model.default_thickness > 0.0f))
        model.default_thickness = suggested_thickness(model.bounds());
}

/// Checks the model's invariants and throws model_error naming the first broken one: at least one
/// strand, consistent offsets and array sizes, finite coordinates, thickness >= 0, transparency in
/// [0, 1], and at least one segment of non-zero length. Zero-length segments inside a model are
/// allowed: they are common in production data and, as in GL, produce no fragments.
HAIRSHADOW_DECL void validate(const hair_model& model);

#if HAIRSHADOW_KERNEL_BODIES
HAIRSHADOW_DECL void validate(const hair_model& model) {
    if (model.strand_offsets.empty() || model.strand_offsets.front() != 0)
        throw model_error("strand offsets must start at 0");
    if (model.strand_count() == 0) throw model_error("the model has no strands");
    for (std::size_t s = 0; s < model.strand_count(); ++s)
        if (model.strand_offsets[s + 1] < model.strand_offsets[s])
            throw model_error("strand " + std::to_string(s) + " has decreasing offsets");
    if (model.strand_offsets.back() != model.points.size())
        throw model_error("strand offsets cover " + std::to_string(model.strand_offsets.back()) + " points but " +
                          std::to_string(model.points.size()) + " are stored");
    auto check_size = [&](std::size_t size, const char* name) {
        if (size != 0 && size != model.points.size())
            throw model_error(std::string(name) + " array has " + std::to_string(size) + " values for " +
                              std::to_string(model.points.size()) + " points");
    };
    check_size(model.thickness.size(), "thickness");
    check_size(model.transparency.size(), "transparency");
    check_size(model.colors.size(), "colour");
    for (std::size_t i = 0; i < model.points.size(); ++i) {
        const auto& p = model.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw model_error("point " + std::to_string(i) + " has a non-finite coordinate");
    }
    auto check_range = [](float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; };
    const float huge = 3.0e38f;
    if (!check_range(model.default_thickness, 0.0f, huge)) throw model_error("default thickness is negative or not finite");
    if (!check_range(model.default_transparency, 0.0f, 1.0f)) throw model_error("default transparency is outside [0, 1]");
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(model.default_color[c])) throw model_error("default colour is not finite");
    for (std::size_t i = 0; i < model.thickness.size(); ++i)
        if (!check_range(model.thickness[i], 0.0f, huge))
            throw model_error("thickness of point " + std::to_string(i) + " is negative or not finite");
    for (std::size_t i = 0; i < model.transparency.size(); ++i)
        if (!check_range(model.transparency[i], 0.0f, 1.0f))
            throw model_error("transparency of point " + std::to_string(i) + " is outside [0, 1]");
    for (std::size_t i = 0; i < model.colors.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(model.colors[i][c])) throw model_error("colour of point " + std::to_string(i) + " is not finite");
    for (std::size_t s = 0; s < model.strand_count(); ++s) {
        auto pts = model.strand(s);
        for (std::size_t i = 1; i < pts.size(); ++i)
            if (pts[i] != pts[i - 1]) return;
    }
    throw model_error("the model has no segment of non-zero length");
}
#endif

} // namespace hairshadow
