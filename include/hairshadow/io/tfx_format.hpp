#pragma once
/// @file
/// AMD TressFX `.tfx`, versions 3 and 4: strands of a fixed point count, little-endian, every array
/// found by a byte offset from the start of the file.
///
/// - **TressFX 3** (`TressFXFileObject` of TressFX 3.1's `TressFXFileFormat.h`, 296 bytes):
///   f32 version (3.x); u32 guide strands; u32 points per strand (4 to 64); u32 follow hairs per guide;
///   i32 both ends immovable; u32 reserved[31]; u32 offsets of the float3 positions, per-strand f32
///   thickness, per-strand texture coordinates, per-point colours, guide indices and per-point texture
///   coordinates (0 = absent); u32 reserved[32]. The file holds the guides only: TressFX grows the
///   follow hairs when it loads them (see grow_follow_hair).
/// - **TressFX 4** (`TressFXTFXFileHeader`, 160 bytes): f32 version (4.x); u32 strands; u32 points per
///   strand; u32 offsets of the float4 positions (w = 0 at pinned points), strand UVs, vertex UVs,
///   per-strand f32 thickness and vertex colours (0 = absent); u32 reserved[32].

#include <hairshadow/config.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/io/detail/binary_file.hpp>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <string>

namespace hairshadow {

/// A TressFX file's strands and what its header says of them.
struct tfx_contents {
    hair_model strands;                       ///< the strands the file stores (TressFX 3: the guides)
    int major_version = 0;                    ///< 3 or 4
    float version = 0.0f;                     ///< as stored, e.g. 3.0 or 4.0
    std::uint32_t follow_hairs_per_guide = 0; ///< TressFX 3: the count its loader grows per guide
    bool both_ends_immovable = false;         ///< TressFX 3
};

namespace detail {
inline constexpr std::size_t tfx3_header_bytes = 296;
inline constexpr std::size_t tfx4_header_bytes = 160;

/// Checks an array's offset: absent (0) or past the header; returns whether it is present.
inline bool tfx_array_at(byte_reader& in, std::uint32_t offset, std::size_t header_bytes, const char* what) {
    if (offset == 0) return false;
    if (offset < header_bytes)
        in.fail(std::string(what) + " offset " + std::to_string(offset) + " lies inside the " + std::to_string(header_bytes) + "-byte header");
    in.seek(offset, what);
    return true;
}
} // namespace detail

/// Parses the bytes of a TressFX 3 or 4 file; `name` names it in errors. Throws io_error on malformed
/// content, and on a version other than 3.x or 4.x, naming the version.
HAIRSHADOW_DECL tfx_contents parse_tfx_file(std::span<const unsigned char> bytes, const std::string& name);

/// Reads the strands of a TressFX 3 or 4 file (TressFX 3: the guides), with per-strand thickness when
/// present, spread to the strand's points. Throws io_error naming the file on malformed content.
inline hair_model read_tfx(const std::string& path) { return parse_tfx_file(detail::read_file_bytes(path), path).strands; }

/// Writes a TressFX file of `major_version` 3 or 4: positions and per-strand thickness (each strand's
/// first point's). Throws io_error unless every strand has the same point count (TressFX 3: 4 to 64).
inline void write_tfx(const hair_model& model, const std::string& path, int major_version = 4, std::uint32_t follow_hairs_per_guide = 0) {
    using namespace detail;
    if (major_version != 3 && major_version != 4) throw io_error(path, "TressFX version must be 3 or 4");
    const auto strands = model.strand_count();
    const auto per_strand = strands ? model.strand_size(0) : 0;
    for (std::size_t s = 0; s < strands; ++s)
        if (model.strand_size(s) != per_strand) throw io_error(path, "TressFX needs the same point count in every strand");
    if (per_strand < (major_version == 3 ? 4u : 2u) || (major_version == 3 && per_strand > 64))
        throw io_error(path, "TressFX " + std::to_string(major_version) + " cannot hold strands of " + std::to_string(per_strand) + " points");
    if (model.point_count() * 16 + strands * 4 + tfx3_header_bytes > std::numeric_limits<std::uint32_t>::max())
        throw io_error(path, "too large for TressFX's 32-bit offsets");
    const bool v3 = major_version == 3;
    const std::size_t header_bytes = v3 ? tfx3_header_bytes : tfx4_header_bytes;
    const auto positions = static_cast<std::uint32_t>(header_bytes);
    const auto thickness = static_cast<std::uint32_t>(header_bytes + model.point_count() * (v3 ? 12 : 16));
    byte_writer out;
    out.write(v3 ? 3.0f : 4.0f);
    out.write(static_cast<std::uint32_t>(strands));
    out.write(static_cast<std::uint32_t>(per_strand));
    if (v3) {
        out.write(follow_hairs_per_guide);
        out.write(std::int32_t(0));
        for (int i = 0; i < 31; ++i) out.write(std::uint32_t(0));
        out.write(positions);
        out.write(thickness);
        for (int i = 0; i < 4; ++i) out.write(std::uint32_t(0));
    } else {
        out.write(positions);
        out.write(std::uint32_t(0));
        out.write(std::uint32_t(0));
        out.write(thickness);
        out.write(std::uint32_t(0));
    }
    for (int i = 0; i < 32; ++i) out.write(std::uint32_t(0));
    for (std::size_t s = 0; s < strands; ++s)
        for (std::size_t i = 0; i < per_strand; ++i) {
            const auto& p = model.points[model.strand_offsets[s] + i];
            if (v3) out.write(p);
            else out.write(glm::vec4(p, i == 0 ? 0.0f : 1.0f)); // w = 0 pins the root
        }
    for (std::size_t s = 0; s < strands; ++s) out.write(model.thickness_at(model.strand_offsets[s]));
    out.save(path);
}

#if HAIRSHADOW_KERNEL_BODIES
HAIRSHADOW_DECL tfx_contents parse_tfx_file(std::span<const unsigned char> bytes, const std::string& name) {
    using namespace detail;
    byte_reader in(bytes, name);
    tfx_contents out;
    out.version = in.read<float>("version");
    if (!(out.version >= 3.0f && out.version < 5.0f)) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", double(out.version));
        in.fail(std::string("TressFX version ") + text + " is not one this reader knows (3.x or 4.x)");
    }
    out.major_version = out.version < 4.0f ? 3 : 4;
    const bool v3 = out.major_version == 3;
    const std::size_t header_bytes = v3 ? tfx3_header_bytes : tfx4_header_bytes;
    in.require(1, header_bytes - 4, std::string("TressFX ") + (v3 ? "3" : "4") + " header");

    const auto strands = in.read<std::uint32_t>("strand count");
    const auto per_strand = in.read<std::uint32_t>("points per strand");
    std::uint32_t position_offset = 0, thickness_offset = 0;
    if (v3) {
        out.follow_hairs_per_guide = in.read<std::uint32_t>("follow hairs per guide");
        out.both_ends_immovable = in.read<std::int32_t>("both ends immovable") != 0;
        in.seek(144, "offsets");
        position_offset = in.read<std::uint32_t>("position offset");
        thickness_offset = in.read<std::uint32_t>("thickness offset");
        if (per_strand < 4 || per_strand > 64) in.fail("points per strand is " + std::to_string(per_strand) + "; TressFX 3 allows 4 to 64");
    } else {
        position_offset = in.read<std::uint32_t>("position offset");
        in.read<std::uint32_t>("strand UV offset");
        in.read<std::uint32_t>("vertex UV offset");
        thickness_offset = in.read<std::uint32_t>("thickness offset");
        if (per_strand < 2) in.fail("points per strand is " + std::to_string(per_strand) + "; at least 2 are needed");
    }
    if (strands == 0) in.fail("the model has no strands");
    const std::uint64_t point_total = std::uint64_t(strands) * per_strand;
    if (point_total > std::numeric_limits<std::uint32_t>::max()) in.fail("too many points");
    if (!tfx_array_at(in, position_offset, header_bytes, "position array")) in.fail("the file holds no vertex positions");

    hair_model& model = out.strands;
    if (v3) {
        in.append_array(point_total, model.points, "position array");
    } else {
        const auto xyzw = in.read_array<glm::vec4>(point_total, "position array");
        model.points.resize(xyzw.size());
        std::transform(xyzw.begin(), xyzw.end(), model.points.begin(), [](const glm::vec4& p) { return glm::vec3(p); });
    }
    model.strand_offsets.resize(std::size_t(strands) + 1);
    for (std::uint32_t s = 0; s <= strands; ++s) model.strand_offsets[s] = s * per_strand;
    if (tfx_array_at(in, thickness_offset, header_bytes, "thickness array")) {
        const auto strand_thickness = in.read_array<float>(strands, "thickness array");
        model.thickness.resize(model.points.size());
        for (std::uint32_t s = 0; s < strands; ++s)
            std::fill_n(model.thickness.begin() + std::ptrdiff_t(std::size_t(s) * per_strand), per_strand, strand_thickness[s]);
    }
    ensure_thickness(model);
    model = validated(std::move(model), name);
    return out;
}
#endif

} // namespace hairshadow
