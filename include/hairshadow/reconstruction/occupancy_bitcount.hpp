#pragma once
/// @file
/// Occupancy-map reconstruction (Sintorn & Assarsson 2009, sections 3.1-3.3): one bit per slice says
/// whether any fragment fell in it (OR blending); each slab of consecutive slices stores its exact sum.
/// Each set bit in slab i is worth F_i / S_i (the slab's sum over its set bits), and a query
/// interpolates linearly inside its slice, so the result is exact at slab boundaries. The paper sums
/// fragment counts times a constant shadow weight; with per-fragment alpha we sum each fragment's
/// optical depth b = -ln(1 - alpha), which is the same when every alpha is equal.

#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/core/detail/tail_bytes.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

namespace hairshadow {

/// Occupancy bits per slice plus B slabs of exact sums.
/// @tparam Slabs number of slabs (4 in the paper: one RGBA32F texture)
template <int Slabs>
struct occupancy_bitcount {
    static_assert(Slabs >= 1, "occupancy_bitcount needs at least one slab");
    static constexpr int slab_count = Slabs;
    static constexpr std::string_view name = "occupancy_bitcount";
    static constexpr std::string_view glsl_name = "reconstruction/occupancy_bitcount";

    /// Needs contiguous slices, a whole number of 32-bit words, split evenly into the slabs.
    template <class Placement>
    static constexpr bool accepts = contiguous_layers<Placement>() && Placement::layer_count % 32 == 0 && Placement::layer_count % Slabs == 0;

    /// A texel's maps depend on its fragments as a set where they share one optical depth: every sum
    /// then adds the same b, whatever the order (order_free_maps).
    static constexpr bool fragment_order_free = true;

    template <class Placement, class Accumulation>
    struct storage {
        std::array<std::uint32_t, std::size_t(Placement::layer_count / 32)> bits{};
        std::array<typename Accumulation::value_type, std::size_t(Slabs)> slabs{};
        [[no_unique_address]] detail::tail_bytes<detail::tail_padding<decltype(bits), decltype(slabs)>(), storage> tail{}; // 8-bit slabs' padding
        friend bool operator==(const storage&, const storage&) = default;
    };

    /// The texel's fragments into its bits and slabs.
    template <class Placement, class Accumulation, class Fragment>
    static void build(const Placement& placement, const typename Placement::texel_state& state, std::span<const Fragment> fragments,
                      storage<Placement, Accumulation>& out) {
        constexpr int per_slab = Placement::layer_count / Slabs;
        std::array<typename Accumulation::sum_type, std::size_t(Slabs)> sums{};
        const auto assign = detail::texel_assigner(placement, state);
        if constexpr (std::is_same_v<Accumulation, float_accumulation> && Slabs <= 16) {
            // As interpolation::build: every slab's sum takes b or +0, the same sums bit for bit.
            for (const auto& f : fragments) {
                const int k = assign(f.depth);
                if (k < 0) continue;
                out.bits[std::size_t(k / 32)] |= std::uint32_t(1) << (k % 32);
                const float b = fragment_optical_depth(f);
                const int slab = k / per_slab;
                for (int j = 0; j < Slabs; ++j) sums[std::size_t(j)] += detail::keep_if(slab == j, b);
            }
        } else {
            for (const auto& f : fragments) {
                const int k = assign(f.depth);
                if (k < 0) continue;
                out.bits[std::size_t(k / 32)] |= std::uint32_t(1) << (k % 32);
                sums[std::size_t(k / per_slab)] = Accumulation::add(sums[std::size_t(k / per_slab)], fragment_optical_depth(f));
            }
        }
        for (std::size_t i = 0; i < std::size_t(Slabs); ++i) out.slabs[i] = Accumulation::store(sums[i]);
    }

    /// The build in pieces, for a build that meets a texel's fragments among other texels' (in each
    /// texel's own order all the same; methods/detail/streamed_tile.hpp): each fragment's bit set and its
    /// optical depth added to its slab's sum, as build does, then stored. The same maps as build, bit
    /// for bit: build's branch-free loop adds +0 to the other slabs, which changes no sum. It pays
    /// where the slices are chosen sixteen fragments at a time (placement/detail/assign_each.hpp); with them
    /// chosen fragment by fragment, grouping was faster (BENCHMARKS.md, "Full rebuilds", the entry on
    /// layers chosen sixteen fragments at a time).
    template <class Placement, class Accumulation>
    struct accumulator {
        std::array<std::uint32_t, std::size_t(Placement::layer_count / 32)> bits{};
        std::array<typename Accumulation::sum_type, std::size_t(Slabs)> sums{};
    };
    template <class Placement, class Accumulation>
    static void accumulate(accumulator<Placement, Accumulation>& a, int k, float optical_depth) noexcept {
        if (k < 0) return;
        constexpr int per_slab = Placement::layer_count / Slabs;
        a.bits[std::size_t(k / 32)] |= std::uint32_t(1) << (k % 32);
        a.sums[std::size_t(k / per_slab)] = Accumulation::add(a.sums[std::size_t(k / per_slab)], optical_depth);
    }
    template <class Placement, class Accumulation>
    static void finish(const accumulator<Placement, Accumulation>& a, storage<Placement, Accumulation>& out) noexcept {
        out.bits = a.bits;
        for (std::size_t i = 0; i < std::size_t(Slabs); ++i) out.slabs[i] = Accumulation::store(a.sums[i]);
    }

    /// Set bits among slices [begin, end).
    template <std::size_t Words>
    static int count_bits(const std::array<std::uint32_t, Words>& bits, int begin, int end) noexcept {
        int n = 0;
        for (int w = begin / 32; w * 32 < end; ++w) {
            std::uint32_t word = bits[std::size_t(w)];
            const int lo = std::max(begin - w * 32, 0), hi = std::min(end - w * 32, 32);
            if (hi < 32) word &= (std::uint32_t(1) << hi) - 1u;
            word &= ~((std::uint32_t(1) << lo) - 1u);
            n += std::popcount(word);
        }
        return n;
    }

    /// Maps a texel stores, for inspection: the slabs (the bits are not optical depths).
    template <class Placement>
    static constexpr int stored_maps = Slabs;
    /// Optical depth through the end of slab k.
    template <class Placement, class Accumulation>
    static float stored_optical_depth(const storage<Placement, Accumulation>& in, int k) noexcept {
        float omega = 0.0f;
        for (int i = 0; i <= k; ++i) omega += Accumulation::decode(in.slabs[std::size_t(i)]);
        return omega;
    }

    /// Optical depth of the fragments in the slices before the slice a fragment at `depth` was
    /// assigned to: the slabs in front, and the set bits of its own slab before its slice, each worth
    /// the slab's mean. Divided by one fragment's b = -ln(1 - alpha) it is the depth order o of
    /// Sintorn & Assarsson 3.4, exact where every fragment of the texel has a slice of its own and
    /// the same alpha.
    template <class Placement, class Accumulation>
    static float optical_depth_in_front(const Placement& placement, const typename Placement::texel_state& state,
                                        const storage<Placement, Accumulation>& in, float depth) noexcept {
        constexpr int S = Placement::layer_count, per_slab = S / Slabs;
        const int k = placement.assign(state, depth); // as the build placed it (the furthest fragment in the last slice)
        float omega = 0.0f;
        const int slab = k < 0 ? Slabs : k / per_slab; // a fragment the placement dropped: behind everything
        for (int i = 0; i < std::min(slab, Slabs); ++i) omega += Accumulation::decode(in.slabs[std::size_t(i)]);
        if (k < 0) return omega;
        const int first = slab * per_slab;
        const int set = count_bits(in.bits, first, first + per_slab);
        if (set == 0) return omega;
        return omega + Accumulation::decode(in.slabs[std::size_t(slab)]) / float(set) * float(count_bits(in.bits, first, k));
    }

    template <class Placement, class Accumulation>
    static float optical_depth(const Placement& placement, const typename Placement::texel_state& state,
                               const storage<Placement, Accumulation>& in, float depth) noexcept {
        constexpr int S = Placement::layer_count, per_slab = S / Slabs;
        const layer_position p = placement.locate(state, depth);
        if (p.index < 0) return 0.0f;
        const int slab = std::min(p.index, S) / per_slab;
        float omega = 0.0f;
        for (int i = 0; i < std::min(slab, Slabs); ++i) omega += Accumulation::decode(in.slabs[std::size_t(i)]);
        if (p.index >= S) return omega;
        const int first = slab * per_slab;
        const int set = count_bits(in.bits, first, first + per_slab);
        if (set == 0) return omega;
        const float per_bit = Accumulation::decode(in.slabs[std::size_t(slab)]) / float(set);
        const bool occupied = (in.bits[std::size_t(p.index / 32)] >> (p.index % 32)) & 1u;
        return omega + per_bit * (float(count_bits(in.bits, first, p.index)) + (occupied ? p.fraction : 0.0f));
    }
};

} // namespace hairshadow
