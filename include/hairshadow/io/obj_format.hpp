#pragma once
/// @file
/// Wavefront OBJ, read by a small parser of its own: `v` lines are vertices, `l` polylines become
/// strands, `f` faces an opaque triangle mesh; every other statement is skipped, and materials
/// (`mtllib`) are never opened. Every number is checked against its text: a coordinate that is not
/// finite or does not fit a float, and an index that is zero, overflows or names a vertex not yet
/// defined, is an io_error naming the line.
///
/// Faces are fanned from their first vertex: exact for the triangles and convex polygons that
/// exporters write, and linear in the polygon's size (tinyobjloader, used before, was far slower on
/// faces of many thousand vertices).

#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/parse.hpp>
#include <hairshadow/core/triangle_mesh.hpp>
#include <hairshadow/io/detail/binary_file.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hairshadow {

/// What an OBJ file holds: strands (from polylines) and triangles (from faces); either may be empty.
struct obj_contents {
    hair_model hair;
    triangle_mesh mesh;
};

namespace detail {

/// Reads OBJ statements line by line; see the file comment for what is accepted.
class obj_reader {
public:
    obj_reader(std::string_view text, std::string name) : text_(text), name_(std::move(name)) {}

    obj_contents read() {
        obj_contents out;
        std::vector<std::uint32_t> strand;
        std::vector<std::uint32_t> polygon;
        while (next_line()) {
            const auto keyword = token();
            if (keyword == "v") {
                glm::vec3 v;
                for (int c = 0; c < 3; ++c) v[c] = coordinate(token());
                vertices_.push_back(v);
            } else if (keyword == "l") {
                strand.clear();
                for (auto t = token(); !t.empty(); t = token()) strand.push_back(vertex_index(t));
                if (strand.empty()) fail("a polyline ('l') needs at least one vertex");
                out.hair.strand_offsets.push_back(0); // filled below, once the points are copied
                for (const auto i : strand) out.hair.points.push_back(vertices_[i]);
                if (out.hair.points.size() > std::numeric_limits<std::uint32_t>::max()) fail("more than 2^32 strand points");
                out.hair.strand_offsets.back() = static_cast<std::uint32_t>(out.hair.points.size());
            } else if (keyword == "f") {
                polygon.clear();
                for (auto t = token(); !t.empty(); t = token()) polygon.push_back(vertex_index(t));
                if (polygon.size() < 3) fail("a face ('f') needs at least three vertices");
                for (std::size_t k = 1; k + 1 < polygon.size(); ++k) out.mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
            }
        }
        if (!out.mesh.triangles.empty()) out.mesh.vertices = vertices_;
        return out;
    }

private:
    /// Moves to the next line and returns false at the end of the text.
    bool next_line() {
        if (pos_ >= text_.size()) return false;
        const auto end = text_.find('\n', pos_);
        line_ = text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_);
        pos_ = end == std::string_view::npos ? text_.size() : end + 1;
        ++line_number_;
        if (const auto hash = line_.find('#'); hash != std::string_view::npos) line_ = line_.substr(0, hash);
        return true;
    }
    /// The next whitespace-separated field of the line, or an empty view at its end.
    std::string_view token() {
        const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; };
        std::size_t i = 0;
        while (i < line_.size() && is_space(line_[i])) ++i;
        std::size_t j = i;
        while (j < line_.size() && !is_space(line_[j])) ++j;
        const auto field = line_.substr(i, j - i);
        line_ = line_.substr(j);
        return field;
    }
    float coordinate(std::string_view field) {
        if (field.empty()) fail("a vertex ('v') needs three coordinates");
        float value = 0.0f;
        const auto status = parse_float(field, value);
        if (status == number_status::too_large) fail("coordinate '" + std::string(field) + "' does not fit a float");
        if (status == number_status::malformed) fail("'" + std::string(field) + "' is not a number");
        if (!std::isfinite(value)) fail("coordinate '" + std::string(field) + "' is not finite");
        return value;
    }
    /// The zero-based vertex of a `v`, `v/vt`, `v//vn` or `v/vt/vn` field; negative indices count back
    /// from the last vertex defined.
    std::uint32_t vertex_index(std::string_view field) {
        const auto digits = field.substr(0, field.find('/'));
        long long index = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
        if (ec == std::errc::result_out_of_range) fail("vertex index '" + std::string(digits) + "' is out of range");
        if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty())
            fail("'" + std::string(field) + "' is not a vertex index");
        const auto count = static_cast<long long>(vertices_.size());
        const long long zero_based = index > 0 ? index - 1 : count + index;
        if (index == 0 || zero_based < 0 || zero_based >= count)
            fail("vertex index " + std::to_string(index) + " is out of range (" + std::to_string(count) + " vertices defined so far)");
        return static_cast<std::uint32_t>(zero_based);
    }
    [[noreturn]] void fail(const std::string& reason) const { throw io_error(name_, "line " + std::to_string(line_number_) + ": " + reason); }

    std::string_view text_;
    std::string name_;
    std::size_t pos_ = 0;
    std::size_t line_number_ = 0;
    std::string_view line_;
    std::vector<glm::vec3> vertices_;
};

} // namespace detail

/// Parses the text of an OBJ file; `name` names it in errors. Throws io_error on anything malformed.
inline obj_contents parse_obj(std::span<const unsigned char> bytes, const std::string& name) {
    return detail::obj_reader(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), name).read();
}

/// Reads an OBJ file. Throws io_error naming the file when it cannot be read or parsed.
inline obj_contents read_obj(const std::string& path) { return parse_obj(detail::read_file_bytes(path), path); }

/// The strands of parsed OBJ contents; throws io_error when there is no usable polyline.
inline hair_model obj_hair(obj_contents contents, const std::string& name) {
    if (contents.hair.strand_count() == 0) throw io_error(name, "the OBJ file holds no polylines ('l' lines) to use as strands");
    ensure_thickness(contents.hair);
    return detail::validated(std::move(contents.hair), name);
}

/// Reads the strands of an OBJ file; throws io_error when it holds no usable polyline.
inline hair_model read_obj_hair(const std::string& path) { return obj_hair(read_obj(path), path); }

} // namespace hairshadow
