#pragma once
/// @file
/// How far a method's transmittance curves lie from the exact ones: for every texel whose fragments
/// span a depth range, the mean of |T_method(z) - T_exact(z)| over that range, from the first fragment
/// to the last (the integral divided by the span), averaged over those texels. Unlike the error at
/// hair points it does not rest on a convention for a point's own fragment: it weighs the whole curve
/// inside the hair, where the shadow is.

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/fragment.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace hairshadow {

/// The mean transmittance-curve error of `method` against `exact` over the texels of `fragments`
/// (the fragments both were built from, which give each texel's span) with a span, by the midpoint
/// rule with `samples` depths a texel; 0 when no texel has a span. Both maps answer
/// transmittance(x, y, depth). Deterministic for any thread count.
template <class Method, class Exact>
double transmittance_curve_error(const Method& method, const Exact& exact, const fragment_buffer& fragments, int samples = 64,
                                 const execution& exec = {}) {
    if (samples < 1 || samples > 1 << 16) throw argument_error("transmittance curve error: samples must be in [1, 65536]");
    const int res = fragments.resolution();
    struct row_sum {
        double error = 0.0;
        std::size_t texels = 0;
    };
    std::vector<row_sum> rows(static_cast<std::size_t>(res));
    parallel_for(std::size_t(res), exec, [&](std::size_t y) {
        for (int x = 0; x < res; ++x) {
            const auto in = fragments.texel(x, int(y));
            if (in.empty()) continue;
            float lo = in[0].depth, hi = lo;
            for (const auto& f : in) lo = std::min(lo, f.depth), hi = std::max(hi, f.depth);
            if (!(hi > lo)) continue;
            double sum = 0.0;
            for (int i = 0; i < samples; ++i) {
                const float z = lo + (hi - lo) * (float(i) + 0.5f) / float(samples);
                sum += std::abs(double(method.transmittance(x, int(y), z)) - double(exact.transmittance(x, int(y), z)));
            }
            rows[y].error += sum / double(samples);
            ++rows[y].texels;
        }
    });
    double error = 0.0;
    std::size_t texels = 0;
    for (const auto& r : rows) error += r.error, texels += r.texels; // in row order: the same sum for any thread count
    return texels ? error / double(texels) : 0.0;
}

} // namespace hairshadow
