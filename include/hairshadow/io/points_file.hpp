#pragma once
/// @file
/// Query points as text: one `x y z` per line; blank lines and lines starting with `#` are skipped.

#include <hairshadow/core/parse.hpp>
#include <hairshadow/io/detail/binary_file.hpp>

#include <glm/vec3.hpp>

#include <algorithm>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hairshadow {

/// Parses the text of a points file; `name` names it in errors. Throws io_error naming the line on a
/// line without exactly three finite numbers.
inline std::vector<glm::vec3> parse_points(std::span<const unsigned char> bytes, const std::string& name) {
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    std::vector<glm::vec3> points;
    std::size_t number = 0;
    for (auto line : detail::split(text, '\n')) {
        ++number;
        const auto fail = [&](const std::string& why) { throw io_error(name, "line " + std::to_string(number) + ": " + why); };
        int count = 0;
        glm::vec3 p(0.0f);
        for (std::size_t i = 0;;) {
            i = line.find_first_not_of(" \t\r\f\v", i);
            if (i == std::string_view::npos || (count == 0 && line[i] == '#')) break;
            const auto end = std::min(line.find_first_of(" \t\r\f\v", i), line.size());
            if (count == 3) fail("more than three numbers");
            try {
                p[count++] = detail::parse_number<float>(line.substr(i, end - i), "coordinate");
            } catch (const argument_error& e) {
                fail(e.what());
            }
            i = end;
        }
        if (count == 0) continue;
        if (count != 3) fail("expected three numbers 'x y z'");
        points.push_back(p);
    }
    return points;
}

/// Reads a points file. Throws io_error naming the file on any malformed line.
inline std::vector<glm::vec3> read_points(const std::string& path) { return parse_points(detail::read_file_bytes(path), path); }

} // namespace hairshadow
