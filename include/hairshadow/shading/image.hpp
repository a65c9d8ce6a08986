#pragma once
/// @file
/// A linear-RGB float image, top row first, and its 8-bit sRGB encoding for PNG files.

#include <hairshadow/core/error.hpp>

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace hairshadow {

struct image {
    int width = 0, height = 0;
    std::vector<glm::vec3> pixels; ///< linear RGB, row by row from the top

    image() = default;
    image(int w, int h, const glm::vec3& fill) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h), fill) {}
    glm::vec3& at(int x, int y) noexcept { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    const glm::vec3& at(int x, int y) const noexcept { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }

    /// 8-bit sRGB, three channels per pixel.
    std::vector<std::uint8_t> to_srgb8() const {
        std::vector<std::uint8_t> out(pixels.size() * 3);
        for (std::size_t i = 0; i < pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) out[3 * i + std::size_t(c)] = encode(pixels[i][c]);
        return out;
    }
    static std::uint8_t encode(float linear) noexcept {
        const float v = std::clamp(linear, 0.0f, 1.0f);
        const float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
        return std::uint8_t(std::lround(255.0f * s));
    }
};

/// `hi` averaged over `factor` x `factor` blocks (a box filter): a supersampled render brought down to
/// its size. The sides of `hi` must be multiples of `factor`.
inline image downsample(const image& hi, int factor) {
    if (factor < 1 || hi.width % factor != 0 || hi.height % factor != 0) throw argument_error("downsample: the sides must be multiples of the factor");
    image out(hi.width / factor, hi.height / factor, glm::vec3(0.0f));
    const float weight = 1.0f / float(factor * factor);
    for (int y = 0; y < hi.height; ++y)
        for (int x = 0; x < hi.width; ++x) out.at(x / factor, y / factor) += weight * hi.at(x, y);
    return out;
}

/// Mean absolute difference of two images' sRGB values, in [0, 1]; the sizes must agree.
inline double mean_absolute_difference(const image& a, const image& b) {
    const auto x = a.to_srgb8(), y = b.to_srgb8();
    if (x.size() != y.size() || x.empty()) return 1.0;
    double sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sum += std::abs(int(x[i]) - int(y[i]));
    return sum / (255.0 * double(x.size()));
}

} // namespace hairshadow
