#pragma once
/// @file
/// Reconstruction by interpolation: each layer (opacity map, deep opacity layer or density cluster bin)
/// stores its optical depth, and the optical depth at a query depth rises linearly across the layer it
/// falls in (Kim & Neumann 2001 section 2; Yuksel & Keyser 2008 section 3; Mertens et al. 2004 section
/// 3.2: piecewise-constant density, piecewise-linear optical depth).

#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/accumulation/detail/repeated_sums.hpp>
#include <hairshadow/placement/detail/assign_each.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

namespace hairshadow {

/// Optical depth interpolated linearly inside each layer.
struct interpolation {
    static constexpr std::string_view name = "interpolation";
    static constexpr std::string_view glsl_name = "reconstruction/interpolation";

    /// Any placement's layers can be interpolated.
    template <class Placement>
    static constexpr bool accepts = Placement::layer_count >= 1;

    /// A texel's maps depend on its fragments as a set where they share one optical depth: every sum
    /// then adds the same b, whatever the order (order_free_maps).
    static constexpr bool fragment_order_free = true;

    /// One value per layer: cumulative (the optical depth in front of the layer's end) when the
    /// placement's layers are opacity maps, per bin when they are histogram bins.
    template <class Placement, class Accumulation>
    struct storage {
        std::array<typename Accumulation::value_type, std::size_t(Placement::layer_count)> layers{};
        friend bool operator==(const storage&, const storage&) = default;
    };

    /// Sums the texel's fragments into its layers; `instructions` (resolved) chooses how the layers
    /// are found (placement/detail/assign_each.hpp), which changes no bit.
    template <class Placement, class Accumulation, class Fragment>
    static void build(const Placement& placement, const typename Placement::texel_state& state, std::span<const Fragment> fragments,
                      storage<Placement, Accumulation>& out, instruction_set instructions = instruction_set::scalar) {
        constexpr int L = Placement::layer_count;
        std::array<typename Accumulation::sum_type, std::size_t(L)> sums{};
        if (!fragments.empty() && one_optical_depth(fragments)) {
            // Every fragment adds the same b, so a layer's sum is a function of how many it took: counted
            // (sixteen at a time where the placement can), then read from this thread's repeated_sums,
            // not added fragment by fragment: the same sums, bit for bit, without a chain of dependent
            // adds per layer (BENCHMARKS.md, "A texel of one optical depth sums its layers from their
            // counts").
            return finish_counted<Placement, Accumulation>(fragment_optical_depth(fragments[0]),
                                                           detail::layer_counts(placement, state, fragments, instructions), out);
        }
        detail::for_each_layer(placement, state, fragments, instructions, [&sums](int k, const Fragment& f) {
            if constexpr (std::is_same_v<Accumulation, float_accumulation> && L <= 16) {
                // Every layer's sum takes b or +0 for every fragment: the same sums, bit for bit (x + 0 == x
                // for the sums, which are never -0), without a store and reload of one layer's sum per
                // fragment; the layers' adds are independent and vectorise.
                const float b = fragment_optical_depth(f);
                for (int j = 0; j < L; ++j) sums[std::size_t(j)] += detail::keep_if(k == j, b);
            } else {
                if (k >= 0) sums[std::size_t(k)] = Accumulation::add(sums[std::size_t(k)], fragment_optical_depth(f));
            }
        });
        finish<Placement, Accumulation>(sums, out);
    }

#if HAIRSHADOW_AVX512_WALK
    /// build for a texel whose fragments all have optical depth b, given by their depths alone
    /// (tile_fragments::group_depths): build's branch for one optical depth, the same maps bit for bit.
    template <class Placement, class Accumulation>
        requires requires(const Placement& p, const typename Placement::texel_state& s, std::span<const float> depths,
                          std::array<std::uint32_t, std::size_t(Placement::layer_count)>& counts) { p.count_texel_avx512(s, depths, counts); }
    static void build_from_depths(const Placement& placement, const typename Placement::texel_state& state, std::span<const float> depths, float b,
                                  storage<Placement, Accumulation>& out) {
        std::array<std::uint32_t, std::size_t(Placement::layer_count)> counts{};
        placement.count_texel_avx512(state, depths, counts);
        finish_counted<Placement, Accumulation>(b, counts, out);
    }
#endif

    /// Whether every fragment's optical depth is the first one's: their alphas (or optical depths) are,
    /// bit for bit. Without a branch per fragment, so that the loop vectorises.
    template <class Fragment>
    static bool one_optical_depth(std::span<const Fragment> fragments) noexcept {
        const auto source = [](const Fragment& f) {
            if constexpr (requires { f.alpha; }) return std::bit_cast<std::uint32_t>(f.alpha);
            else return std::bit_cast<std::uint32_t>(f.optical_depth);
        };
        const std::uint32_t first = source(fragments[0]);
        std::uint32_t other = 0;
        for (const auto& f : fragments) other |= source(f) ^ first;
        return other == 0;
    }

    /// The maps of a texel whose fragments all add b, counts[k] of them in layer k.
    template <class Placement, class Accumulation>
    static void finish_counted(float b, const std::array<std::uint32_t, std::size_t(Placement::layer_count)>& counts,
                               storage<Placement, Accumulation>& out) {
        auto& repeats = detail::repeated_sums_of<Accumulation>(b);
        std::array<typename Accumulation::sum_type, std::size_t(Placement::layer_count)> sums{};
        for (std::size_t k = 0; k < sums.size(); ++k) sums[k] = repeats(counts[k]);
        finish<Placement, Accumulation>(sums, out);
    }

    /// The build in pieces, for a build that meets a texel's fragments among other texels' (in each
    /// texel's own order all the same): one accumulator per texel, each fragment accumulated into its
    /// layer k (as assign gives it), then finished. The same maps as build, bit for bit: build's
    /// branch-free loop adds +0 to the other layers, which changes no sum.
    template <class Placement, class Accumulation>
    using accumulator = std::array<typename Accumulation::sum_type, std::size_t(Placement::layer_count)>;
    template <class Placement, class Accumulation>
    static void accumulate(accumulator<Placement, Accumulation>& sums, int k, float optical_depth) noexcept {
        if (k >= 0) sums[std::size_t(k)] = Accumulation::add(sums[std::size_t(k)], optical_depth);
    }
    template <class Placement, class Accumulation>
    static void finish(const accumulator<Placement, Accumulation>& sums, storage<Placement, Accumulation>& out) noexcept {
        typename Accumulation::sum_type running{};
        for (std::size_t k = 0; k < std::size_t(Placement::layer_count); ++k) {
            if constexpr (Placement::cumulative) {
                running = Accumulation::combine(running, sums[k]);
                out.layers[k] = Accumulation::store(running);
            } else {
                out.layers[k] = Accumulation::store(sums[k]);
            }
        }
    }
    /// finish for several texels, the same values: their running sums advance layer by layer side by
    /// side, so that each texel's chain of dependent adds overlaps the others' (64 opacity maps: a
    /// chain of 64 adds per texel; BENCHMARKS.md, "Many layers streamed").
    template <class Placement, class Accumulation, std::size_t N>
        requires(Placement::cumulative)
    static void finish_several(const std::array<const accumulator<Placement, Accumulation>*, N>& sums,
                               const std::array<storage<Placement, Accumulation>*, N>& out) noexcept {
        std::array<typename Accumulation::sum_type, N> running{};
        for (std::size_t k = 0; k < std::size_t(Placement::layer_count); ++k)
            for (std::size_t t = 0; t < N; ++t) {
                running[t] = Accumulation::combine(running[t], (*sums[t])[k]);
                out[t]->layers[k] = Accumulation::store(running[t]);
            }
    }

    /// Optical depth in front of the end of layer k.
    template <class Placement, class Accumulation>
    static float through_layer(const storage<Placement, Accumulation>& in, int k) noexcept {
        if (k < 0) return 0.0f;
        if constexpr (Placement::cumulative) {
            return Accumulation::decode(in.layers[std::size_t(k)]);
        } else {
            float sum = 0.0f;
            for (int i = 0; i <= k; ++i) sum += Accumulation::decode(in.layers[std::size_t(i)]);
            return sum;
        }
    }

    /// Maps a texel stores, for inspection: one per layer.
    template <class Placement>
    static constexpr int stored_maps = Placement::layer_count;
    /// Optical depth stored through map k (the end of layer k).
    template <class Placement, class Accumulation>
    static float stored_optical_depth(const storage<Placement, Accumulation>& in, int k) noexcept {
        return through_layer<Placement, Accumulation>(in, k);
    }

    template <class Placement, class Accumulation>
    static float optical_depth(const Placement& placement, const typename Placement::texel_state& state,
                               const storage<Placement, Accumulation>& in, float depth) noexcept {
        constexpr int L = Placement::layer_count;
        const layer_position p = placement.locate(state, depth);
        if (p.index < 0) return 0.0f;
        if (p.index >= L) return through_layer<Placement, Accumulation>(in, L - 1);
        const float before = through_layer<Placement, Accumulation>(in, p.index - 1);
        const float after = through_layer<Placement, Accumulation>(in, p.index);
        return before + p.fraction * (after - before);
    }
};

} // namespace hairshadow
