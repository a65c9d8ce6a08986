#pragma once
/// @file
/// Small text parsing helpers for the spec grammars (model, light, method).

#include <hairshadow/core/error.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
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

enum class number_status { ok, malformed, too_large };

/// Reads all of `text` as a float (an optional leading '+' allowed). A value below the smallest float
/// reads as its nearest float (0 or subnormal), as strtof gives it: libstdc++'s from_chars reports
/// such underflow as out of range, like overflow, so strtof tells the two apart.
inline number_status parse_float(std::string_view text, float& value) {
    if (!text.empty() && text[0] == '+') {
        text.remove_prefix(1);
        if (!text.empty() && (text[0] == '+' || text[0] == '-')) return number_status::malformed;
    }
    const auto* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ptr != end || ec == std::errc::invalid_argument) return number_status::malformed;
    if (ec == std::errc::result_out_of_range) {
        const float nearest = std::strtof(std::string(text).c_str(), nullptr);
        if (!(std::abs(nearest) <= std::numeric_limits<float>::min())) return number_status::too_large;
        value = nearest;
    }
    return number_status::ok;
}

template <class T>
T parse_number(std::string_view text, std::string_view what) {
    T value{};
    if constexpr (std::is_same_v<T, float>) {
        if (parse_float(text, value) != number_status::ok)
            throw argument_error(std::string(what) + ": '" + std::string(text) + "' is not a valid number");
    } else {
        const auto* end = text.data() + text.size();
        auto [ptr, ec] = std::from_chars(text.data(), end, value);
        if (ec != std::errc() || ptr != end || text.empty())
            throw argument_error(std::string(what) + ": '" + std::string(text) + "' is not a valid number");
    }
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(value)) throw argument_error(std::string(what) + ": '" + std::string(text) + "' is not finite");
    return value;
}
} // namespace detail

} // namespace hairshadow
