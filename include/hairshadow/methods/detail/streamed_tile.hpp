#pragma once
/// @file
/// The tiled build without grouping fragments by texel, for methods whose per-texel work is a running
/// reduction: a placement whose texel state follows from the texel's nearest and furthest fragment
/// (texel_state_from), and a reconstruction that accumulates one fragment at a time (accumulator,
/// accumulate, finish). The tile's fragments are read twice in walk order, where they already lie:
/// once for each texel's depth range, once to add each fragment into its texel's layer. Each texel
/// still meets its own fragments in the walk's order (segment order, or one that the maps cannot
/// tell from it: order_free_maps), so the maps are the grouped build's, bit for bit;
/// what it saves is the counting sort, whose scattered writes miss the cache on a dense tile. The
/// layers are chosen a block of fragments at a time (placement/detail/assign_each.hpp: sixteen a step with
/// AVX-512), then added one by one, in walk order. Only the texels that took fragments are finished;
/// with many layers, eight at a time (finish_several).

#include <hairshadow/placement/detail/assign_each.hpp>
#include <hairshadow/policies/capabilities.hpp>
#include <hairshadow/placement/layer_position.hpp>
#include <hairshadow/raster/detail/tile_fragments.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

namespace hairshadow::detail {

/// A texel's depth range as its nearest depth and minus its furthest. Both bounds then follow from
/// one packed minimum, {min(d, nearest), min(-d, -furthest)}, with min(a, b) = a < b ? a : b:
/// widen_extent's comparisons, negated in the second (-max(d, f) = min(-d, -f), signed
/// zeros alike), and one 8-byte store a fragment where it made two (BENCHMARKS.md, "Full rebuilds",
/// the entry on the depth pass in one packed minimum).
struct negated_range {
    float nearest, neg_furthest;
};
inline bool empty_range(const negated_range& range) noexcept { return !(range.nearest <= -range.neg_furthest); }

#if HAIRSHADOW_AVX512_WALK
/// add_depths with the pair in one register (VEX-encoded SSE: the AVX-512 target's broadcast from
/// memory saves a shuffle over plain SSE2). _mm_min_ps(a, b) is a < b ? a : b, lane by lane.
HAIRSHADOW_AVX512_TARGET inline void add_depths_avx512(negated_range* ranges, const std::uint32_t* where, const float* depth, std::size_t n) noexcept {
    static_assert(sizeof(negated_range) == sizeof(double));
    const __m128 negate_second = _mm_setr_ps(0.0f, -0.0f, 0.0f, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        double* r = reinterpret_cast<double*>(ranges + where[i]);
        const __m128 d = _mm_xor_ps(_mm_broadcast_ss(depth + i), negate_second);
        _mm_store_sd(r, _mm_castps_pd(_mm_min_ps(d, _mm_castpd_ps(_mm_load_sd(r)))));
    }
}
#endif

/// The depth pass: each of n fragments' depth into its texel's range, in walk order; `instructions`
/// (resolved) chooses the path, both the same bits.
inline void add_depths(negated_range* ranges, const std::uint32_t* where, const float* depth, std::size_t n, instruction_set instructions) noexcept {
#if HAIRSHADOW_AVX512_WALK
    if (instructions == instruction_set::avx512) return add_depths_avx512(ranges, where, depth, n);
#else
    (void)instructions;
#endif
    for (std::size_t i = 0; i < n; ++i) {
        negated_range& r = ranges[where[i]];
        const float d = depth[i], nearest = d < r.nearest ? d : r.nearest, neg_furthest = -d < r.neg_furthest ? -d : r.neg_furthest;
        r = {nearest, neg_furthest};
    }
}

/// Whether a tile of this build may be walked in any order: the composition's maps are order free
/// and no segment end, so no fragment, has depth -0. Every fragment's depth is a + ((b - a) s)
/// rounded, s in [0, 1], between ends a and b of one sign (`extent` holds every end): it has their
/// sign, or is +0 where the two terms cancel exactly, and is -0 only where an end is.
template <class Placement, class Reconstruction>
bool walks_in_any_order(const depth_extent& extent) noexcept {
    if constexpr (order_free_maps<Placement, Reconstruction>) return extent.nearest > 0.0f || extent.furthest < 0.0f;
    else return false;
}

/// One thread's working memory for the streamed build: per texel of a tile, its depth range, placement
/// state and accumulator. Kept from tile to tile and from build to build.
template <class Placement, class Accumulation, class Reconstruction>
class streamed_tile {
public:
    using state = typename Placement::texel_state;
    using accumulator = typename Reconstruction::template accumulator<Placement, Accumulation>;

    /// Room for tiles of `texels` texels, so that no tile allocates.
    void reserve(std::size_t texels) {
        ranges_.reserve(texels), states_.reserve(texels), sums_.reserve(texels), touched_.reserve(texels), filled_.reserve(texels);
    }

    /// Whether streaming `tile` beats grouping it. Always without per-texel state (nothing but the
    /// adds); with it, where the tile holds at least `dense` fragments a texel. In a sparse tile the
    /// per-texel passes, not the grouping, are most of the work, and grouping is the cheaper build
    /// there (BENCHMARKS.md, "Full rebuilds", the entry on streamed tiles).
    static constexpr std::size_t dense = 4;
    static bool pays(const tile_fragments& tile) noexcept {
        const texel_rect r = tile.rect();
        return std::is_empty_v<state> || tile.size() >= dense * std::size_t(r.x1 - r.x0) * std::size_t(r.y1 - r.y0);
    }

    /// Builds the texels of `tile` (gathered in walk order) into texel_out(x, y), a texel_maps with
    /// .placement and .data, which it overwrites. `instructions` (resolved) chooses assign_each's path.
    template <class TexelOut>
    void build(const Placement& placement, const tile_fragments& tile, instruction_set instructions, TexelOut&& texel_out) {
        const texel_rect r = tile.rect();
        const int width = r.x1 - r.x0;
        const std::size_t texels = std::size_t(width) * std::size_t(r.y1 - r.y0);
        const auto where = tile.walk_texels();
        const auto depth = tile.walk_depths();
        const auto optical = tile.walk_optical_depths();
        const std::size_t n = where.size();
        states_.resize(texels); // read only where a fragment fell, and then written first
        if constexpr (finish_later) {
            // The accumulators are left zero after every tile (each filled one is reset once finished),
            // so a tile clears none: with many layers, clearing them all cost more than the tile's adds.
            if (!sums_zero_) sums_.assign(sums_.size(), accumulator{});
            if (sums_.size() < texels) sums_.resize(texels);
            sums_zero_ = false;
        } else {
            sums_.assign(texels, accumulator{});
        }
        // The depth pass (texel_extent_of, fragment by fragment), without a branch: every range starts
        // empty, [+inf, -inf] (stored negated_range {+inf, +inf}), so that the first fragment's min and max give {d, d}, as texel_extent_of
        // starts, and the later ones the same results in the same order. The depths are finite (the
        // model's points are), so a texel is empty where its range still is. A placement without
        // per-texel state needs no depth pass: the texels the walk names are marked instead (below).
        constexpr bool stateful = !std::is_empty_v<state>;
        constexpr float inf = std::numeric_limits<float>::infinity();
        if constexpr (stateful) {
            ranges_.assign(texels, negated_range{inf, inf});
            add_depths(ranges_.data(), where.data(), depth.data(), n, instructions);
            for (std::size_t k = 0; k < texels; ++k)
                if (!empty_range(ranges_[k])) placement.texel_state_from(ranges_[k].nearest, -ranges_[k].neg_furthest, states_[k]);
        }
        // Each fragment's optical depth, or the tile's one (the vector walk keeps no other).
        if (const std::optional<float> b = tile.tile_optical_depth()) add_layers(placement, where, depth, instructions, [b](std::size_t) { return *b; });
        else add_layers(placement, where, depth, instructions, [optical](std::size_t i) { return optical[i]; });
        // Which texels took a fragment: those whose depth range is not empty, or, without a depth
        // pass, those the walk names.
        if constexpr (!stateful) {
            touched_.assign(texels, 0);
            for (std::size_t i = 0; i < n; ++i) touched_[where[i]] = 1;
        }
        // A texel without fragments gets the maps of empty sums, as finish gives them.
        using texel_maps = std::remove_reference_t<decltype(texel_out(r.x0, r.y0))>;
        texel_maps blank{};
        if constexpr (!stateful) Reconstruction::template finish<Placement, Accumulation>(accumulator{}, blank.data);
        filled_.clear();
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                const std::size_t k = std::size_t(y - r.y0) * std::size_t(width) + std::size_t(x - r.x0);
                auto& out = texel_out(x, y);
                const bool filled = stateful ? !empty_range(ranges_[k]) : touched_[k] != 0;
                out = blank;
                if (!filled) continue;
                out.placement = states_[k];
                if constexpr (finish_later) filled_.push_back({std::uint32_t(k), &out.data});
                else Reconstruction::template finish<Placement, Accumulation>(sums_[k], out.data);
            }
        if constexpr (finish_later) {
            finish_filled();
            sums_zero_ = true;
        }
    }

    std::size_t memory_bytes() const noexcept {
        return ranges_.capacity() * sizeof(negated_range) + states_.capacity() * sizeof(state) + sums_.capacity() * sizeof(accumulator) +
               touched_.capacity() + filled_.capacity() * sizeof(filled_texel);
    }

private:
    using storage = typename Reconstruction::template storage<Placement, Accumulation>;

    /// Adds each fragment to its texel's layer (chosen a block at a time), in walk order, with optical
    /// depth optical_at(i) for fragment i.
    template <class OpticalAt>
    HAIRSHADOW_ALWAYS_INLINE void add_layers(const Placement& placement, std::span<const std::uint32_t> where, std::span<const float> depth,
                                             instruction_set instructions, OpticalAt optical_at) {
        std::array<std::int32_t, block> layers;
        for (std::size_t first = 0; first < where.size(); first += block) {
            const std::size_t count = std::min(block, where.size() - first);
            assign_each(placement, std::span<const state>(states_), where.subspan(first, count), depth.subspan(first, count),
                        std::span(layers).first(count), instructions);
            for (std::size_t i = 0; i < count; ++i)
                Reconstruction::template accumulate<Placement, Accumulation>(sums_[where[first + i]], layers[i], optical_at(first + i));
        }
    }
    /// A texel that took fragments: its index in the tile and its maps' stored layers.
    struct filled_texel {
        std::uint32_t k;
        storage* out;
    };
    static constexpr std::size_t together = 8;
    /// Whether the filled texels are finished after the tile's texels are walked, eight at a time: where
    /// the reconstruction finishes several in one call (interpolation's cumulative layers, a chain of
    /// dependent adds per texel) and the chains are long. With few layers, finishing each texel in
    /// place measured faster.
    static constexpr bool finish_later = Placement::layer_count > 16 && requires(std::array<const accumulator*, together> in,
                                                                                 std::array<storage*, together> out) {
        Reconstruction::template finish_several<Placement, Accumulation>(in, out);
    };
    /// Finishes every filled texel's accumulator into its maps, eight at a time so that their chains
    /// overlap, and resets the accumulator.
    void finish_filled() noexcept {
        std::size_t i = 0;
        for (; i + together <= filled_.size(); i += together) {
            std::array<const accumulator*, together> in;
            std::array<storage*, together> out;
            for (std::size_t j = 0; j < together; ++j) in[j] = &sums_[filled_[i + j].k], out[j] = filled_[i + j].out;
            Reconstruction::template finish_several<Placement, Accumulation>(in, out);
        }
        for (; i < filled_.size(); ++i) Reconstruction::template finish<Placement, Accumulation>(sums_[filled_[i].k], *filled_[i].out);
        for (const filled_texel& t : filled_) sums_[t.k] = accumulator{};
    }

    /// Fragments whose layers are chosen at a time: a block's layers stay in the first-level cache.
    static constexpr std::size_t block = 512;

    std::vector<negated_range> ranges_;
    std::vector<state> states_;
    std::vector<accumulator> sums_;
    bool sums_zero_ = true;             ///< every accumulator zero (false only while a tile builds)
    std::vector<std::uint8_t> touched_; ///< per texel, whether the walk named it (without a depth pass)
    std::vector<filled_texel> filled_;
};

/// Stands in for streamed_tile in a composition that does not stream.
struct no_streamed_tile {
    std::size_t memory_bytes() const noexcept { return 0; }
};

template <class Placement, class Accumulation, class Reconstruction>
using streamed_tile_for = typename std::conditional_t<streams_tiles<Placement, Accumulation, Reconstruction>,
                                                      std::type_identity<streamed_tile<Placement, Accumulation, Reconstruction>>,
                                                      std::type_identity<no_streamed_tile>>::type;

} // namespace hairshadow::detail
