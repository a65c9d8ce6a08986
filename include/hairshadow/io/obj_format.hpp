#pragma once
/// @file
/// Wavefront OBJ through tinyobjloader: `l` polylines become strands, faces an opaque triangle mesh.
/// Needs tinyobjloader (Debian's libtinyobjloader-dev): link the `hairshadow::io` target, or
/// `tinyobjloader::tinyobjloader`, when including this header.

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/triangle_mesh.hpp>
#include <hairshadow/io/binary_file.hpp>

#include <tiny_obj_loader.h>

#include <cmath>
#include <filesystem>

namespace hairshadow {

/// What an OBJ file holds: strands (from polylines) and triangles (from faces); either may be empty.
struct obj_contents {
    hair_model hair;
    triangle_mesh mesh;
};

/// Reads an OBJ file. Throws io_error naming the file when it cannot be parsed, an index is out of
/// range, or a coordinate is not finite.
inline obj_contents read_obj(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw io_error(path, "no such file");
    if (std::filesystem::file_size(path, ec) > HAIRSHADOW_MAX_FILE_BYTES) throw io_error(path, "file is larger than the configured maximum");
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string message = reader.Error();
        while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
        throw io_error(path, message.empty() ? "cannot parse OBJ" : message);
    }
    const auto& coords = reader.GetAttrib().vertices;
    const std::size_t vertex_count = coords.size() / 3;
    auto vertex = [&](int index) {
        if (index < 0 || std::size_t(index) >= vertex_count)
            throw io_error(path, "vertex index " + std::to_string(index + 1) + " is out of range (" + std::to_string(vertex_count) + " vertices)");
        glm::vec3 v(coords[3 * std::size_t(index)], coords[3 * std::size_t(index) + 1], coords[3 * std::size_t(index) + 2]);
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) throw io_error(path, "a vertex has a non-finite coordinate");
        return v;
    };
    obj_contents out;
    for (const auto& shape : reader.GetShapes()) {
        std::size_t next = 0;
        for (int n : shape.lines.num_line_vertices) {
            if (n < 0 || next + std::size_t(n) > shape.lines.indices.size()) throw io_error(path, "a polyline's vertex list is truncated");
            std::vector<glm::vec3> strand;
            strand.reserve(std::size_t(n));
            for (int i = 0; i < n; ++i) strand.push_back(vertex(shape.lines.indices[next + std::size_t(i)].vertex_index));
            next += std::size_t(n);
            out.hair.add_strand(strand);
        }
        const auto& idx = shape.mesh.indices;
        for (std::size_t f = 0; f < idx.size(); f += 3) {
            if (f + 2 >= idx.size()) throw io_error(path, "a face's vertex list is truncated");
            std::array<std::uint32_t, 3> tri{};
            for (int k = 0; k < 3; ++k) {
                vertex(idx[f + std::size_t(k)].vertex_index); // range and finiteness check
                tri[std::size_t(k)] = static_cast<std::uint32_t>(idx[f + std::size_t(k)].vertex_index);
            }
            out.mesh.triangles.push_back(tri);
        }
    }
    if (!out.mesh.triangles.empty())
        for (std::size_t i = 0; i < vertex_count; ++i) out.mesh.vertices.push_back(vertex(int(i)));
    return out;
}

/// Reads the strands of an OBJ file; throws io_error when it holds no usable polyline.
inline hair_model read_obj_hair(const std::string& path) {
    auto contents = read_obj(path);
    if (contents.hair.strand_count() == 0) throw io_error(path, "the OBJ file holds no polylines ('l' lines) to use as strands");
    ensure_thickness(contents.hair);
    return detail::validated(std::move(contents.hair), path);
}

} // namespace hairshadow
