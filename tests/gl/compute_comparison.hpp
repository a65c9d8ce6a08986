#pragma once
// GL maps read back against the CPU maps of the same method, every texel: which texels hold a
// fragment, states and bitmasks bit for bit, float sums relative to the CPU's. Shared by the
// compute-path tests and bench/gl_gpu_check.
#include <hairshadow/gl.hpp>
#include <hairshadow/methods/detail/tiled_build.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <vector>

namespace test {

struct map_comparison {
    long occupied = 0;      ///< texels with a fragment, by the GPU's range map
    long occupied_cpu = 0;  ///< texels with a fragment, by the CPU's walk of the same model
    long occupancy_off = 0; ///< texels with a fragment on one side only
    long state_off = 0;     ///< texels whose placement state differs in any bit
    long data_off = 0;      ///< stored values off: bits or counts at all, 8-bit levels at all, float sums by more than float_tolerance relative
    double worst = 0.0;     ///< the largest relative difference of a float sum
    long levels_off = 0;    ///< 8-bit projected sums one level apart (counted in data_off when further)
    bool exact() const noexcept { return occupied == occupied_cpu && occupancy_off == 0 && state_off == 0 && data_off == 0; }
};

/// How far a float sum on GL may lie from the CPU's, relative: the compute path sums in fixed point
/// where the CPU adds floats in order, so the two round differently (docs/policies.md, "GL").
inline constexpr double float_tolerance = 1e-6;
/// How far a projected method's sum on GL may lie from the CPU's, relative to the texel's largest sum
/// (reported in `worst` scaled to float_tolerance).
inline constexpr double projection_tolerance = 1e-5;

/// Which texels of `light`'s map `model` makes a fragment in, by the CPU's own walk (tile by tile, no
/// fragment buffer): one byte a texel, row by row.
inline std::vector<unsigned char> cpu_occupancy(const hairshadow::hair_model& model, const hairshadow::light_space& light,
                                                const hairshadow::raster_options& options = {}) {
    const std::size_t res = std::size_t(light.resolution());
    std::vector<unsigned char> occupied(res * res, 0);
    hairshadow::detail::tiled_workspace w;
    w.bins.prepare(model, light, options, true);
    hairshadow::detail::for_each_tile(w, hairshadow::detail::tile_grouping::walk_order, [&](unsigned, const hairshadow::detail::tile_fragments& tile) {
        const auto& r = tile.rect();
        const auto width = std::uint32_t(r.x1 - r.x0);
        for (const std::uint32_t k : tile.walk_texels()) // each tile's own texels: no two threads write one
            occupied[(std::size_t(r.y0) + k / width) * res + std::size_t(r.x0) + k % width] = 1;
    });
    return occupied;
}

template <class T>
void compare_value(map_comparison& c, T cpu, T gl) {
    if constexpr (std::is_floating_point_v<T>) {
        const double error = std::abs(double(cpu) - double(gl)) / std::max(std::abs(double(cpu)), 1e-3);
        c.worst = std::max(c.worst, error);
        c.data_off += error > float_tolerance;
    } else {
        c.data_off += cpu != gl;
    }
}

/// `on_gl` read back against `cpu`, every texel: where the GPU's range map `range` (read_range) or
/// the CPU's walk (`occupied`, cpu_occupancy) finds no fragment, both maps must hold the empty texel
/// (zeros), and the two must agree on which texels those are.
template <class Method>
map_comparison compare_maps(const Method& cpu, hairshadow::gl::maps<Method>& on_gl, const std::vector<float>& range,
                            const std::vector<unsigned char>& occupied, int res) {
    const auto texels = on_gl.read_back();
    map_comparison c;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(res) + std::size_t(x);
            const bool on_gpu = range[4 * i] <= range[4 * i + 3], on_cpu = occupied[i] != 0;
            c.occupied += on_gpu;
            c.occupied_cpu += on_cpu;
            c.occupancy_off += on_gpu != on_cpu;
            const auto& a = cpu.texel(x, y);
            const auto& b = texels[i];
            if constexpr (!std::is_empty_v<decltype(a.placement)>) c.state_off += std::memcmp(&a.placement, &b.placement, sizeof a.placement) != 0;
            if constexpr (requires { a.data.layers; }) {
                for (std::size_t k = 0; k < a.data.layers.size(); ++k) compare_value(c, a.data.layers[k], b.data.layers[k]);
            } else if constexpr (requires { a.data.bits; }) {
                c.data_off += a.data.bits != b.data.bits;
                for (std::size_t k = 0; k < a.data.slabs.size(); ++k) compare_value(c, a.data.slabs[k], b.data.slabs[k]);
            } else if constexpr (requires { requires !std::is_floating_point_v<std::remove_cvref_t<decltype(a.data.sums[0])>>; }) {
                // 8-bit steps of encoded terms, each rounded to a level from a term whose cosine GL
                // and the C library may round apart: a level off now and then.
                for (std::size_t k = 0; k < a.data.sums.size(); ++k) {
                    const int levels = std::abs(int(a.data.sums[k]) - int(b.data.sums[k]));
                    c.levels_off += levels == 1;
                    c.data_off += levels > 1;
                }
            } else if constexpr (requires { a.data.sums; }) {
                // Signed sums that may cancel to near zero (a Fourier coefficient, an odd moment), of
                // terms whose cosines GL and the C library round apart: each within
                // projection_tolerance of the texel's largest sum.
                double scale = 1e-3;
                for (const float v : a.data.sums) scale = std::max(scale, double(std::abs(v)));
                for (std::size_t k = 0; k < a.data.sums.size(); ++k) {
                    const double error = std::abs(double(a.data.sums[k]) - double(b.data.sums[k])) / scale;
                    c.worst = std::max(c.worst, error / (projection_tolerance / float_tolerance));
                    c.data_off += error > projection_tolerance;
                }
            } else if constexpr (requires { a.data.nodes; }) {
                c.data_off += !(a.data == b.data); // adaptive nodes: chosen from the same bits, so the same bits
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
