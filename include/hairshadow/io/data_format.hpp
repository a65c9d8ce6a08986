#pragma once
/// @file
/// USC-HairSalon `.data`: i32 strand count; per strand an i32 point count and that many float3 points.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/io/detail/binary_file.hpp>

#include <limits>
#include <span>

namespace hairshadow {

/// Parses the bytes of a USC-HairSalon `.data` file; `name` names it in errors. Throws io_error on
/// malformed content.
inline hair_model parse_data(std::span<const unsigned char> bytes, const std::string& name) {
    using namespace detail;
    byte_reader in(bytes, name);
    const auto strands = in.read<std::int32_t>("strand count");
    if (strands <= 0) in.fail("strand count is " + std::to_string(strands) + "; at least 1 is needed");
    in.require(std::uint64_t(strands), 4, "strand headers"); // each strand needs at least its count
    hair_model model;
    model.strand_offsets.reserve(std::size_t(strands) + 1);
    for (std::int32_t s = 0; s < strands; ++s) {
        const auto n = in.read<std::int32_t>("point count");
        if (n < 0) in.fail("strand " + std::to_string(s) + " has a negative point count");
        in.require(std::uint64_t(n), 12, "strand " + std::to_string(s));
        if (model.points.size() + std::size_t(n) > std::numeric_limits<std::uint32_t>::max()) in.fail("too many points");
        in.append_array(std::uint64_t(n), model.points, "strand " + std::to_string(s));
        model.strand_offsets.push_back(static_cast<std::uint32_t>(model.points.size()));
    }
    if (in.remaining() != 0) in.fail(std::to_string(in.remaining()) + " trailing bytes after the last strand");
    ensure_thickness(model);
    return validated(std::move(model), name);
}

/// Reads a USC-HairSalon `.data` file. Throws io_error naming the file on malformed content.
inline hair_model read_data(const std::string& path) { return parse_data(detail::read_file_bytes(path), path); }

/// Writes a USC-HairSalon `.data` file (positions only; the format has no other arrays).
inline void write_data(const hair_model& model, const std::string& path) {
    detail::byte_writer out;
    if (model.strand_count() > std::size_t(std::numeric_limits<std::int32_t>::max())) throw io_error(path, "too many strands for .data");
    out.write(static_cast<std::int32_t>(model.strand_count()));
    for (std::size_t s = 0; s < model.strand_count(); ++s) {
        out.write(static_cast<std::int32_t>(model.strand_size(s)));
        for (const auto& p : model.strand(s)) out.write(p);
    }
    out.save(path);
}

} // namespace hairshadow
