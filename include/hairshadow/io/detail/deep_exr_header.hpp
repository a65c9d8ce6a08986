#pragma once
/// @file
/// The attributes of a hairshadow deep OpenEXR file (io/deep_exr.hpp): the light that maps world
/// points to texels and depths, bit for bit (light_space::parts), the method spec and tolerance, the
/// library's version and what Z means. Needs OpenEXR.

#include <hairshadow/config.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>

#include <ImfFloatAttribute.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfStringAttribute.h>

#include <optional>
#include <string>

namespace hairshadow::detail {

/// Attribute names: namespaced, so that they sit beside any other program's.
namespace exr_attribute {
inline constexpr const char* resolution = "hairshadow/resolution";
inline constexpr const char* light_type = "hairshadow/lightType";
inline constexpr const char* view = "hairshadow/view";
inline constexpr const char* projection = "hairshadow/projection";
inline constexpr const char* view_projection = "hairshadow/viewProjection";
inline constexpr const char* near_plane = "hairshadow/near";
inline constexpr const char* far_plane = "hairshadow/far";
inline constexpr const char* half_extent = "hairshadow/halfExtent";
inline constexpr const char* method = "hairshadow/method";
inline constexpr const char* tolerance = "hairshadow/tolerance";
inline constexpr const char* version = "hairshadow/version";
inline constexpr const char* depth = "hairshadow/depth";
} // namespace exr_attribute

/// A glm matrix (column-vector convention, m[column][row]) as Imath's (row-vector convention, x[row][column]):
/// the transpose, which is the same sixteen floats in the same order.
inline Imath::M44f to_imath(const glm::mat4& m) {
    Imath::M44f out;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out.x[i][j] = m[i][j];
    return out;
}
inline glm::mat4 to_glm(const Imath::M44f& m) {
    glm::mat4 out;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out[i][j] = m.x[i][j];
    return out;
}

inline const char* light_type_name(light_type type) {
    return type == light_type::directional ? "directional" : type == light_type::point ? "point" : "spot";
}

/// Writes the light, the method spec, the tolerance (where compressed) and the version into `h`.
inline void write_hairshadow_attributes(Imf::Header& h, const light_space& light, const std::string& method, std::optional<float> tolerance) {
    const light_space_parts p = light.parts();
    h.insert(exr_attribute::resolution, Imf::IntAttribute(p.resolution));
    h.insert(exr_attribute::light_type, Imf::StringAttribute(light_type_name(p.type)));
    h.insert(exr_attribute::view, Imf::M44fAttribute(to_imath(p.view)));
    h.insert(exr_attribute::projection, Imf::M44fAttribute(to_imath(p.projection)));
    h.insert(exr_attribute::view_projection, Imf::M44fAttribute(to_imath(p.view_projection)));
    h.insert(exr_attribute::near_plane, Imf::FloatAttribute(p.near_plane));
    h.insert(exr_attribute::far_plane, Imf::FloatAttribute(p.far_plane));
    h.insert(exr_attribute::half_extent, Imf::FloatAttribute(p.half_extent));
    h.insert(exr_attribute::method, Imf::StringAttribute(method));
    if (tolerance) h.insert(exr_attribute::tolerance, Imf::FloatAttribute(*tolerance));
    h.insert(exr_attribute::version, Imf::StringAttribute(std::to_string(HAIRSHADOW_VERSION_MAJOR) + "." + std::to_string(HAIRSHADOW_VERSION_MINOR) +
                                                          "." + std::to_string(HAIRSHADOW_VERSION_PATCH)));
    h.insert(exr_attribute::depth, Imf::StringAttribute("Z is the light's linear depth in [0, 1]: distance = near + Z * (far - near), "
                                                        "along the light's axis (hairshadow/near, hairshadow/far)"));
}

/// The attribute `name` of type T, or an io_error naming it.
template <class T>
const T& required_attribute(const Imf::Header& h, const char* name, const std::string& file) {
    const auto* a = h.findTypedAttribute<T>(name);
    if (!a) throw io_error(file, std::string("no ") + name + " attribute of the right type: the light is needed to map world points to texels");
    return *a;
}

/// The light stored by write_hairshadow_attributes; io_error naming the first attribute missing or wrong.
inline light_space read_light_attributes(const Imf::Header& h, const std::string& file) {
    light_space_parts p;
    p.resolution = required_attribute<Imf::IntAttribute>(h, exr_attribute::resolution, file).value();
    const std::string type = required_attribute<Imf::StringAttribute>(h, exr_attribute::light_type, file).value();
    if (type == "directional") p.type = light_type::directional;
    else if (type == "point") p.type = light_type::point;
    else if (type == "spot") p.type = light_type::spot;
    else throw io_error(file, std::string(exr_attribute::light_type) + " is '" + type + "', not directional, point or spot");
    p.view = to_glm(required_attribute<Imf::M44fAttribute>(h, exr_attribute::view, file).value());
    p.projection = to_glm(required_attribute<Imf::M44fAttribute>(h, exr_attribute::projection, file).value());
    p.view_projection = to_glm(required_attribute<Imf::M44fAttribute>(h, exr_attribute::view_projection, file).value());
    p.near_plane = required_attribute<Imf::FloatAttribute>(h, exr_attribute::near_plane, file).value();
    p.far_plane = required_attribute<Imf::FloatAttribute>(h, exr_attribute::far_plane, file).value();
    p.half_extent = required_attribute<Imf::FloatAttribute>(h, exr_attribute::half_extent, file).value();
    try {
        return light_space::from_parts(p);
    } catch (const argument_error& e) {
        throw io_error(file, std::string("the stored light is not usable: ") + e.what());
    }
}

/// A string attribute, or "" where there is none.
inline std::string optional_string(const Imf::Header& h, const char* name) {
    const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
    return a ? a->value() : std::string();
}

} // namespace hairshadow::detail
