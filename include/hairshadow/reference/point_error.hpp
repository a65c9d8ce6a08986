#pragma once
/// @file
/// How far a method's transmittance lies from the exact one at a set of points (the hair's own, in
/// `compare` and the figure): the mean, 95th percentile and maximum of |T_method - T_exact|.

#include <hairshadow/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace hairshadow {

/// The error of a method's transmittance at some points against the exact transmittance there.
struct point_error {
    double mean = 0.0; ///< mean |T - T_exact|
    double p95 = 0.0;  ///< the error at rank floor(0.95 n) of the n errors sorted (0-based; the largest for n < 20)
    double max = 0.0;  ///< the largest
    std::size_t points = 0;
};

/// The error of `t` against `exact`, point by point; all zero for no points. Throws argument_error
/// where the two differ in length.
inline point_error point_error_of(std::span<const float> t, std::span<const float> exact) {
    if (t.size() != exact.size()) throw argument_error("point error: the method's and the exact transmittance differ in length");
    point_error e;
    e.points = t.size();
    if (t.empty()) return e;
    std::vector<float> error(t.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) sum += error[i] = std::abs(t[i] - exact[i]);
    std::sort(error.begin(), error.end());
    e.mean = sum / double(error.size());
    e.p95 = error[std::min(error.size() - 1, std::size_t(0.95 * double(error.size())))];
    e.max = error.back();
    return e;
}

} // namespace hairshadow
