#pragma once
// GL maps read back against the CPU maps of the same method, texel by texel: states and bitmasks bit
// for bit, float sums relative to the CPU's. Shared by the compute-path tests and bench/gl_gpu_check.
#include <hairshadow/gl.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <vector>

namespace test {

struct map_comparison {
    long occupied = 0;  ///< texels with a fragment
    long state_off = 0; ///< of those, texels whose placement state differs in any bit
    long data_off = 0;  ///< stored values off: bits or counts at all, 8-bit levels at all, float sums by more than 1e-5 relative
    double worst = 0.0; ///< the largest relative difference of a float sum
    bool exact() const noexcept { return state_off == 0 && data_off == 0; }
};

template <class T>
void compare_value(map_comparison& c, T cpu, T gl) {
    if constexpr (std::is_floating_point_v<T>) {
        const double error = std::abs(double(cpu) - double(gl)) / std::max(std::abs(double(cpu)), 1e-3);
        c.worst = std::max(c.worst, error);
        c.data_off += error > 1e-5;
    } else {
        c.data_off += cpu != gl;
    }
}

/// `on_gl` read back against `cpu`, at the texels where the range map `range` (read_range) has a
/// fragment: the read-back leaves the others zero, where the CPU keeps its empty state.
template <class Method>
map_comparison compare_maps(const Method& cpu, hairshadow::gl::maps<Method>& on_gl, const std::vector<float>& range, int res) {
    const auto texels = on_gl.read_back();
    map_comparison c;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(res) + std::size_t(x);
            if (range[4 * i] > range[4 * i + 3]) continue;
            ++c.occupied;
            const auto& a = cpu.texel(x, y);
            const auto& b = texels[i];
            if constexpr (!std::is_empty_v<decltype(a.placement)>) c.state_off += std::memcmp(&a.placement, &b.placement, sizeof a.placement) != 0;
            if constexpr (requires { a.data.layers; }) {
                for (std::size_t k = 0; k < a.data.layers.size(); ++k) compare_value(c, a.data.layers[k], b.data.layers[k]);
            } else if constexpr (requires { a.data.bits; }) {
                c.data_off += a.data.bits != b.data.bits;
                for (std::size_t k = 0; k < a.data.slabs.size(); ++k) compare_value(c, a.data.slabs[k], b.data.slabs[k]);
            } else if constexpr (requires { a.data.fragments; }) {
                c.data_off += a.data.fragments != b.data.fragments;
                compare_value(c, a.data.optical_depth, b.data.optical_depth);
            } else {
                c.data_off += a.data.any != b.data.any;
            }
        }
    return c;
}

} // namespace test
