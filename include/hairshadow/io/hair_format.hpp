#pragma once
/// @file
/// Cem Yuksel's `.hair` format: a 128-byte header, then the arrays that its bit field announces.
///
/// Header: "HAIR", u32 strands, u32 points, u32 bit field (1 segments, 2 points, 4 thickness,
/// 8 transparency, 16 colour), u32 default segments, f32 default thickness, f32 default transparency,
/// f32[3] default colour, char[88] information. Arrays in that order: u16 segments per strand, f32[3]
/// points, f32 thickness, f32 transparency, f32[3] colour. All little-endian.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/io/detail/binary_file.hpp>

#include <bit>
#include <cstring>
#include <limits>
#include <span>

namespace hairshadow {

namespace detail {
static_assert(std::endian::native == std::endian::little, "hairshadow's readers assume a little-endian host");
inline constexpr std::uint32_t hair_has_segments = 1u << 0;
inline constexpr std::uint32_t hair_has_points = 1u << 1;
inline constexpr std::uint32_t hair_has_thickness = 1u << 2;
inline constexpr std::uint32_t hair_has_transparency = 1u << 3;
inline constexpr std::uint32_t hair_has_color = 1u << 4;
} // namespace detail

/// Parses the bytes of a `.hair` file; `name` names it in errors. Throws io_error on any malformed or
/// truncated content.
inline hair_model parse_hair(std::span<const unsigned char> bytes, const std::string& name) {
    using namespace detail;
    byte_reader in(bytes, name);
    if (bytes.size() < 128) in.fail("truncated: the header needs 128 bytes but the file has " + std::to_string(bytes.size()));
    char magic[4];
    std::memcpy(magic, bytes.data(), 4);
    if (std::memcmp(magic, "HAIR", 4) != 0) in.fail("not a .hair file (the magic is not \"HAIR\")");
    in.seek(4, "header");
    const auto strands = in.read<std::uint32_t>("strand count");
    const auto point_total = in.read<std::uint32_t>("point count");
    const auto fields = in.read<std::uint32_t>("bit field");
    const auto default_segments = in.read<std::uint32_t>("default segments");
    hair_model model;
    model.default_thickness = in.read<float>("default thickness");
    model.default_transparency = in.read<float>("default transparency");
    for (int c = 0; c < 3; ++c) model.default_color[c] = in.read<float>("default colour");
    in.seek(128, "data");

    if (!(fields & hair_has_points)) in.fail("the bit field announces no points array");
    if (fields & ~std::uint32_t(31)) in.fail("unknown bits in the bit field");
    if (strands == 0) in.fail("the model has no strands");
    // A strand holds at least one point, and every point takes 12 bytes: both bound the counts before
    // anything is allocated or looped over.
    if (strands > point_total) in.fail(std::to_string(strands) + " strands cannot share " + std::to_string(point_total) + " points");
    in.require(strands, fields & hair_has_segments ? 2 : 0, "segments array");
    in.require(point_total, 12, "points array");

    std::vector<std::uint16_t> segments;
    if (fields & hair_has_segments) {
        segments = in.read_array<std::uint16_t>(strands, "segments array");
    } else if (default_segments > std::numeric_limits<std::uint16_t>::max()) {
        in.fail("default segment count " + std::to_string(default_segments) + " exceeds 65535");
    }
    std::uint64_t expected_points = 0;
    for (std::uint32_t s = 0; s < strands; ++s)
        expected_points += std::uint64_t(segments.empty() ? default_segments : segments[s]) + 1;
    if (expected_points != point_total)
        in.fail("the strands hold " + std::to_string(expected_points) + " points but the header says " +
                std::to_string(point_total));
    const std::size_t per_point = 12 + (fields & hair_has_thickness ? 4 : 0) + (fields & hair_has_transparency ? 4 : 0) +
                                  (fields & hair_has_color ? 12 : 0);
    in.require(point_total, per_point, "point arrays");

    model.points = in.read_array<glm::vec3>(point_total, "points array");
    if (fields & hair_has_thickness) model.thickness = in.read_array<float>(point_total, "thickness array");
    if (fields & hair_has_transparency) model.transparency = in.read_array<float>(point_total, "transparency array");
    if (fields & hair_has_color) model.colors = in.read_array<glm::vec3>(point_total, "colour array");

    model.strand_offsets.resize(std::size_t(strands) + 1);
    model.strand_offsets[0] = 0;
    for (std::uint32_t s = 0; s < strands; ++s)
        model.strand_offsets[s + 1] = model.strand_offsets[s] + (segments.empty() ? default_segments : segments[s]) + 1;
    ensure_thickness(model);
    return validated(std::move(model), name);
}

/// Reads a `.hair` file. Throws io_error naming the file on any malformed or truncated content.
inline hair_model read_hair(const std::string& path) { return parse_hair(detail::read_file_bytes(path), path); }

/// Writes a `.hair` file holding every array the model has. Strands of more than 65536 points or of
/// none cannot be stored in the format and raise io_error.
inline void write_hair(const hair_model& model, const std::string& path) {
    using namespace detail;
    if (model.point_count() > std::numeric_limits<std::uint32_t>::max()) throw io_error(path, "too many points for .hair");
    byte_writer out;
    out.write(std::array<char, 4>{'H', 'A', 'I', 'R'});
    out.write(static_cast<std::uint32_t>(model.strand_count()));
    out.write(static_cast<std::uint32_t>(model.point_count()));
    std::uint32_t fields = hair_has_segments | hair_has_points;
    if (!model.thickness.empty()) fields |= hair_has_thickness;
    if (!model.transparency.empty()) fields |= hair_has_transparency;
    if (!model.colors.empty()) fields |= hair_has_color;
    out.write(fields);
    out.write(std::uint32_t(0));
    out.write(model.default_thickness);
    out.write(model.default_transparency);
    out.write(model.default_color);
    std::array<char, 88> info{};
    std::memcpy(info.data(), "written by hairshadow", 21);
    out.write(info);
    std::vector<std::uint16_t> segments(model.strand_count());
    for (std::size_t s = 0; s < model.strand_count(); ++s) {
        const auto n = model.strand_size(s);
        if (n == 0 || n - 1 > std::numeric_limits<std::uint16_t>::max())
            throw io_error(path, "strand " + std::to_string(s) + " has " + std::to_string(n) + " points; .hair holds 1 to 65536");
        segments[s] = static_cast<std::uint16_t>(n - 1);
    }
    out.write_array(segments);
    out.write_array(model.points);
    out.write_array(model.thickness);
    out.write_array(model.transparency);
    out.write_array(model.colors);
    out.save(path);
}

} // namespace hairshadow
