#pragma once
/// @file
/// Any method's optical depth as deep volume samples (io/deep_exr.hpp, write_sampled_deep_exr): the
/// function sampled at a set of depths, one volume sample an interval. Needs no OpenEXR.

#include <hairshadow/io/detail/deep_exr_samples.hpp>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <span>
#include <string>
#include <vector>

namespace hairshadow {

/// What write_sampled_deep_exr needs of a map: its light and its optical depth in front of any depth
/// of any texel (any_shadow_map, a shadow_method, the reference maps, deep_exr_map).
template <class Map>
concept optical_depth_map = requires(const Map& m, int x, float depth) {
    { m.light() } -> std::convertible_to<const light_space&>;
    { m.optical_depth(x, x, depth) } -> std::convertible_to<float>;
};

namespace detail {

/// The spec a map names (any_shadow_map::spec().text) where `given` is empty; else `given`.
template <class Map>
std::string method_text(const Map& map, const std::string& given) {
    if (!given.empty()) return given;
    if constexpr (requires { map.spec().text; }) return std::string(map.spec().text);
    else return given;
}

/// The depths write_sampled_deep_exr samples every texel at: samples + 1 uniform depths over the
/// light's [0, 1], i / samples rounded to float.
inline std::vector<float> uniform_sample_depths(int samples) {
    std::vector<float> depths(std::size_t(samples) + 1);
    for (int i = 0; i <= samples; ++i) depths[std::size_t(i)] = float(double(i) / double(samples));
    return depths;
}

/// One texel's optical depth omega(depth), sampled at `depths` (increasing), as deep samples: a point
/// sample at depths[0] where omega is positive there, then one volume sample over [z_{i-1}, z_i] for
/// each interval over which omega rises past its largest value so far, its alpha taking the
/// composited transmittance to exp(-omega(z_i)). Where omega falls (occupancy's estimates, series
/// and moments ringing, a compressed map within its tolerance), the samples keep its largest value so far until it rises past it again: compositing
/// gives exp(-max over z_j <= z of omega(z_j)) at each sample depth z (exp(-omega) wherever omega
/// has not fallen in front), and in between optical depth linear in depth, OpenEXR's volume rule.
/// `level` tracks the transmittance the float alphas so far composite to, so that rounding does not
/// drift; below 1e-7 nothing more is written (every later value is within 1e-7 of it).
template <class Omega>
void sampled_texel_samples(std::span<const float> depths, Omega&& omega, std::vector<deep_sample>& out) {
    double level = 1.0, most = 0.0;
    for (std::size_t i = 0; i < depths.size() && level >= 1e-7; ++i) {
        const double w = double(omega(depths[i]));
        if (!(w > most)) continue; // no rise (or NaN): nothing to write
        most = w;
        const float alpha = std::min(float(1.0 - std::exp(-most) / level), std::nextafter(1.0f, 0.0f));
        if (!(alpha > 0.0f)) continue;
        out.push_back({i == 0 ? depths[0] : depths[i - 1], depths[i], alpha});
        level *= 1.0 - double(alpha);
    }
}

} // namespace detail
} // namespace hairshadow
