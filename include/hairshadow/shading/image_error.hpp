#pragma once
/// @file
/// The difference a person sees between two renders of one scene, over the hair: per pixel, the mean
/// over the three channels of |sRGB a - sRGB b| (the 8-bit values a PNG holds, as fractions of 255),
/// at the pixels the hair covers; its mean and 99th percentile. Unlike the error at hair points it
/// does not rest on a convention for a point's own fragment, and it weighs what the camera sees.

#include <hairshadow/core/error.hpp>
#include <hairshadow/shading/image.hpp>

#include <algorithm>
#include <cstdlib>
#include <span>
#include <vector>

namespace hairshadow {

struct image_difference {
    double mean = 0.0;       ///< mean over the hair's pixels, in [0, 1]
    double p99 = 0.0;        ///< 99th percentile over them
    std::size_t pixels = 0;  ///< pixels the hair covers
};

/// The difference of `a` and `b` at the pixels where `coverage` (hair_coverage, one value a pixel) is
/// above zero; all zero where the hair covers none.
inline image_difference image_error(const image& a, const image& b, std::span<const float> coverage) {
    if (a.width != b.width || a.height != b.height || coverage.size() != a.pixels.size())
        throw argument_error("image error: the images and the coverage must be the same size");
    const auto x = a.to_srgb8(), y = b.to_srgb8();
    std::vector<double> differences;
    for (std::size_t i = 0; i < coverage.size(); ++i) {
        if (!(coverage[i] > 0.0f)) continue;
        int sum = 0;
        for (std::size_t c = 0; c < 3; ++c) sum += std::abs(int(x[3 * i + c]) - int(y[3 * i + c]));
        differences.push_back(double(sum) / (3.0 * 255.0));
    }
    image_difference d;
    d.pixels = differences.size();
    if (differences.empty()) return d;
    double total = 0.0;
    for (const double v : differences) total += v;
    d.mean = total / double(differences.size());
    const std::size_t rank = std::min(differences.size() - 1, std::size_t(0.99 * double(differences.size())));
    std::nth_element(differences.begin(), differences.begin() + std::ptrdiff_t(rank), differences.end());
    d.p99 = differences[rank];
    return d;
}

} // namespace hairshadow
