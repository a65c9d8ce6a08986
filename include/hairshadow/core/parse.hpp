#pragma once
/// @file
/// Small text parsing helpers for the spec grammars (model, light, method).

#include <hairshadow/core/error.hpp>

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace hairshadow {

namespace detail {
inline std::vector<std::string_view> split(std::string_view text, char sep) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
        const auto end = text.find(sep, start);
        parts.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) return parts;
        start = end + 1;
    }
}

template <class T>
T parse_number(std::string_view text, std::string_view what) {
    T value{};
    const auto* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || text.empty())
        throw argument_error(std::string(what) + ": '" + std::string(text) + "' is not a valid number");
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(value)) throw argument_error(std::string(what) + ": '" + std::string(text) + "' is not finite");
    return value;
}
} // namespace detail

} // namespace hairshadow
