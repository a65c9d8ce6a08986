#pragma once
/// @file
/// AMD TressFX `.tfx` (version 4.0): f32 version; u32 strands; u32 points per strand; u32 byte offsets of
/// the vertex positions, strand UVs, vertex UVs, strand thickness and vertex colours (0 = absent),
/// then reserved words. Positions are float4 (xyz, w = 0 at the pinned root), strand-major.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/io/binary_file.hpp>

#include <cmath>

namespace hairshadow {

/// Reads a TressFX `.tfx` file: positions, and per-strand thickness when present (spread to the
/// strand's points). Throws io_error naming the file on malformed content.
inline hair_model read_tfx(const std::string& path) {
    using namespace detail;
    const auto bytes = read_file_bytes(path);
    byte_reader in(bytes, path);
    if (bytes.size() < 32) in.fail("truncated: the header needs 32 bytes but the file has " + std::to_string(bytes.size()));
    const auto version = in.read<float>("version");
    const auto strands = in.read<std::uint32_t>("strand count");
    const auto per_strand = in.read<std::uint32_t>("points per strand");
    const auto position_offset = in.read<std::uint32_t>("position offset");
    in.read<std::uint32_t>("strand UV offset");
    in.read<std::uint32_t>("vertex UV offset");
    const auto thickness_offset = in.read<std::uint32_t>("thickness offset");
    if (!std::isfinite(version) || version < 1.0f || version > 16.0f) in.fail("not a TressFX file (implausible version)");
    if (strands == 0) in.fail("the model has no strands");
    if (per_strand < 2) in.fail("points per strand is " + std::to_string(per_strand) + "; at least 2 are needed");
    if (position_offset == 0) in.fail("the file holds no vertex positions");
    const std::uint64_t point_total = std::uint64_t(strands) * per_strand;
    if (point_total > std::numeric_limits<std::uint32_t>::max()) in.fail("too many points");
    in.seek(position_offset, "position array");
    const auto xyzw = in.read_array<glm::vec4>(point_total, "position array");

    hair_model model;
    model.points.resize(xyzw.size());
    for (std::size_t i = 0; i < xyzw.size(); ++i) model.points[i] = glm::vec3(xyzw[i]);
    model.strand_offsets.resize(std::size_t(strands) + 1);
    for (std::uint32_t s = 0; s <= strands; ++s) model.strand_offsets[s] = s * per_strand;
    if (thickness_offset != 0) {
        in.seek(thickness_offset, "thickness array");
        const auto strand_thickness = in.read_array<float>(strands, "thickness array");
        model.thickness.resize(model.points.size());
        for (std::uint32_t s = 0; s < strands; ++s)
            std::fill_n(model.thickness.begin() + std::size_t(s) * per_strand, per_strand, strand_thickness[s]);
    }
    ensure_thickness(model);
    return validated(std::move(model), path);
}

} // namespace hairshadow
