#pragma once
/// @file
/// One tile's fragments: the working set of the tiled build. The tile's segments are walked once, by
/// the line rule, into a per-thread store, in walk order; group() then groups the fragments by texel,
/// each texel's in walk order: segment order, the order a fragment_buffer keeps, unless the build let
/// the walk choose its own (fragment_order::any); group_depths() groups the depths alone, where every
/// fragment has one optical depth (one_optical_depth). The walk runs
/// in AVX-512 where the CPU has it (raster/detail/tile_walk_avx512.hpp), else in scalar C++; both give the
/// same fragments, bit for bit.

#include <hairshadow/config.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/detail/huge_pages.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/line_rule.hpp>
#include <hairshadow/raster/instruction_set.hpp>
#include <hairshadow/raster/detail/segment_bins.hpp>
#if HAIRSHADOW_AVX512_WALK
#include <hairshadow/raster/detail/tile_walk_avx512.hpp>
#endif

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace hairshadow {

namespace detail {

/// The order a tile's walk stores its fragments in.
enum class fragment_order {
    /// Segment after segment, in the tile's list: each texel meets its fragments in segment order, the
    /// order of a fragment_buffer, on which sums of different optical depths depend.
    segment,
    /// Any order the walk finds fastest (it sorts the segments by their length in the tile and stores
    /// sixteen at a step), the same for any thread count. Only for a build whose maps depend on each
    /// texel's fragments as a set where they share one optical depth and none is -0 (as the vector
    /// walk's tiles do: order_free_maps); the scalar walk keeps segment order.
    any,
};

/// A tile's fragments with their optical depths, each texel's in segment order (unless walked in any
/// order), so that sums over them match the fragment_buffer build bit for bit. One per thread; its memory is kept from tile to
/// tile and from build to build.
class tile_fragments {
public:
    /// Walks tile t's segments into the store, in walk order: segment after segment, or, where `order`
    /// allows any order and the vector walk runs, in an order of the walk's own (fragment_order).
    /// `instructions` must be resolved.
    HAIRSHADOW_DECL void gather(const segment_bins& bins, std::size_t t, instruction_set instructions, fragment_order order = fragment_order::segment);
    /// Room to sort a tile of `segments` segments and `side` texels a side for the walk in any order,
    /// so that tiles up to that size allocate nothing, on whichever thread they land.
    void reserve_segments(std::size_t segments, int side) {
        if (sorted_.size() < segments) sorted_.resize(segments), steps_.resize(segments);
        steps_of_.reserve(std::size_t(side) + 2);
    }

    /// Whether every fragment a walk of `bins` makes has one optical depth: thin lines of uniform
    /// attributes and one alpha, the tiles the vector walk covers. That b is shared_optical_depth.
    static bool one_optical_depth(const segment_bins& bins) noexcept {
        return bins.options().wide_line_width == 0.0f && bins.uniform_attributes() && bins.uniform_shader().constant_alpha();
    }
    /// The optical depth every fragment has, where one_optical_depth(bins).
    static float shared_optical_depth(const segment_bins& bins) noexcept { return optical_depth_of(bins.uniform_shader().shade(0.0f).alpha); }

    const texel_rect& rect() const noexcept { return rect_; }
    /// Fragments of the tile's texel (x, y), in map coordinates, once grouped (group()).
    std::span<const optical_fragment> texel(int x, int y) const noexcept {
        const std::size_t k = std::size_t(y - rect_.y0) * std::size_t(width_) + std::size_t(x - rect_.x0);
        return {grouped_.data() + offsets_[k], std::size_t(offsets_[k + 1] - offsets_[k])};
    }
    /// Depths of the tile's texel (x, y), in map coordinates, once grouped alone (group_depths()).
    std::span<const float> texel_depths(int x, int y) const noexcept {
        const std::size_t k = std::size_t(y - rect_.y0) * std::size_t(width_) + std::size_t(x - rect_.x0);
        return {grouped_depths_.data() + offsets_[k], std::size_t(offsets_[k + 1] - offsets_[k])};
    }
    /// The last tile's fragments in walk order: segment after segment, as in the tile's list, unless
    /// gather was let walk in any order. Each texel's fragments come in the order texel() gives them. walk_texels() are row-major indices
    /// within the tile.
    std::span<const std::uint32_t> walk_texels() const noexcept { return {where_.data(), n_}; }
    std::span<const float> walk_depths() const noexcept { return {depth_.data(), n_}; }
    /// Each fragment's optical depth, in walk order; empty where the walk kept one for the whole tile
    /// (tile_optical_depth()).
    std::span<const float> walk_optical_depths() const noexcept { return {optical_.data(), tile_optical_ ? 0 : n_}; }
    /// The optical depth of every fragment of the last tile, where the walk kept it once for the tile
    /// rather than once a fragment: the vector walk's tiles, all of one optical depth (one_optical_depth),
    /// which then write 8 bytes a fragment instead of 12 (the array of optical depths stays allocated,
    /// for the scalar walk's tiles).
    std::optional<float> tile_optical_depth() const noexcept { return tile_optical_; }
    /// Fragment i's optical depth in walk order, however the walk kept it.
    float walk_optical_depth(std::size_t i) const noexcept { return tile_optical_ ? *tile_optical_ : optical_[i]; }
    /// Fragments of the last tile.
    std::size_t size() const noexcept { return n_; }
    /// Fragments it walks without allocating.
    std::size_t capacity() const noexcept { return where_.size(); }
    /// Room to walk a tile of `fragments` fragments and group `grouped` of them (group()) and
    /// `grouped_depths` of their depths (group_depths()) without growing, allocated afresh where the
    /// store is smaller: nothing it held is copied.
    void reserve_fresh(std::size_t fragments, std::size_t grouped, std::size_t grouped_depths = 0) {
        if (where_.size() < fragments) {
            where_ = decltype(where_)(), depth_ = decltype(depth_)(), optical_ = decltype(optical_)();
            where_.resize(fragments), depth_.resize(fragments), optical_.resize(fragments);
        }
        if (grouped_.size() < grouped) grouped_ = decltype(grouped_)(), grouped_.resize(grouped);
        if (grouped_depths_.size() < grouped_depths) grouped_depths_ = decltype(grouped_depths_)(), grouped_depths_.resize(grouped_depths);
    }
    /// Fragments it groups without allocating (group()).
    std::size_t grouped_capacity() const noexcept { return grouped_.size(); }
    /// Depths it groups without allocating (group_depths()).
    std::size_t grouped_depths_capacity() const noexcept { return grouped_depths_.size(); }
    /// Makes room to walk `fragments` fragments, group `grouped` of them and `grouped_depths` of their
    /// depths, in tiles of `tile_texels` texels, so that tiles up to those sizes allocate nothing.
    void reserve(std::size_t fragments, std::size_t grouped, std::size_t grouped_depths, std::size_t tile_texels) {
        if (where_.size() < fragments) where_.resize(fragments), depth_.resize(fragments), optical_.resize(fragments);
        if (grouped_.size() < grouped) grouped_.resize(grouped);
        if (grouped_depths_.size() < grouped_depths) grouped_depths_.resize(grouped_depths);
        if (grouped > 0 || grouped_depths > 0) offsets_.reserve(tile_texels + 2);
    }
    std::size_t memory_bytes() const noexcept {
        return (where_.capacity() + offsets_.capacity()) * sizeof(std::uint32_t) +
               (depth_.capacity() + optical_.capacity() + grouped_depths_.capacity()) * sizeof(float) +
               grouped_.capacity() * sizeof(optical_fragment) + (sorted_.capacity() + steps_of_.capacity()) * sizeof(std::uint32_t) +
               steps_.capacity() * sizeof(std::uint16_t);
    }

private:
    /// Room for `extra` more candidates after the n_ kept so far.
    void make_room(std::size_t extra) {
        if (n_ + extra <= where_.size()) return;
        const std::size_t size = std::max(2 * where_.size(), n_ + extra);
        where_.resize(size);
        depth_.resize(size);
        optical_.resize(size);
    }

    /// The b of an alpha, remembered: segments of one model mostly share one alpha, and a log per
    /// segment would cost more than its walk.
    float optical_depth_cached(float alpha) noexcept {
        if (alpha != last_alpha_) last_alpha_ = alpha, last_optical_ = optical_depth_of(alpha);
        return last_optical_;
    }

    /// A candidate of the walk: stored at n_, kept (n_ advanced) when `kept`.
    HAIRSHADOW_ALWAYS_INLINE void store(int x, int y, bool kept, float depth, float optical) noexcept {
        where_[n_] = std::uint32_t((y - rect_.y0) * width_ + (x - rect_.x0));
        depth_[n_] = depth;
        optical_[n_] = optical;
        n_ += kept;
    }

    /// One segment, in scalar C++: the same fragments as the fragment_buffer rasteriser.
    HAIRSHADOW_ALWAYS_INLINE void walk_segment(const segment_shader& s, float wide) {
        const prepared_segment& seg = s.segment();
        if (wide > 0.0f) {
            rasterize_wide_line(seg, wide, rect_, [&](int x, int y, float param, float weight) {
                make_room(1);
                const fragment f = s.shade(param, weight);
                store(x, y, true, f.depth, optical_depth_of(f.alpha));
            });
            return;
        }
        // A thin line makes at most one candidate per texel along its major axis in the tile, plus one
        // where it starts.
        make_room(std::size_t(std::max(width_, rect_.y1 - rect_.y0)) + 1);
        if (s.constant_alpha()) { // b once: the same value shade() gives every fragment
            const float b = optical_depth_cached(s.shade(0.0f).alpha);
            walk_line(seg.a(), seg.b(), rect_, [&](int x, int y, bool kept) HAIRSHADOW_ALWAYS_INLINE { store(x, y, kept, s.depth(s.parameter(x, y)), b); });
        } else {
            walk_line(seg.a(), seg.b(), rect_, [&](int x, int y, bool kept) HAIRSHADOW_ALWAYS_INLINE {
                const fragment f = s.shade(s.parameter(x, y));
                store(x, y, kept, f.depth, kept ? optical_depth_of(f.alpha) : 0.0f);
            });
        }
    }

    /// walk_segment for the vector walk's leftovers, compiled apart from it: inlined into the AVX-512
    /// function, the compiler could fuse the scalar arithmetic into multiply-adds, and the fragments
    /// would no longer be the scalar walk's.
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    void walk_segment_apart(const segment_bins& bins, std::uint32_t segment) { walk_segment(bins.shader(segment), 0.0f); }

    void walk_scalar(const segment_bins& bins, std::size_t t) {
        const float wide = bins.options().wide_line_width;
        bins.for_each_segment(t, [&](const segment_shader& s) HAIRSHADOW_ALWAYS_INLINE { walk_segment(s, wide); });
    }

public:
    /// Groups the last tile's fragments by texel, for texel(): a count, prefix sums and a stable
    /// scatter, so that texel k's fragments end in [offsets_[k], offsets_[k + 1]) in walk order.
    void group() {
        std::uint32_t* cursor = count_texels();
        // Only as large as the tiles grouped (the streamed build groups only sparse ones), grown by half.
        if (grouped_.size() < n_) grouped_.resize(std::max(n_, grouped_.size() + grouped_.size() / 2));
        optical_fragment* grouped = grouped_.data();
        const std::uint32_t* where = where_.data();
        const float* depth = depth_.data();
        if (tile_optical_) {
            const float b = *tile_optical_;
            for (std::size_t i = 0; i < n_; ++i) grouped[cursor[where[i]]++] = {depth[i], b};
            return;
        }
        const float* optical = optical_.data();
        for (std::size_t i = 0; i < n_; ++i) grouped[cursor[where[i]]++] = {depth[i], optical[i]};
    }
    /// group() for the depths alone, for texel_depths(): where every fragment has one optical depth
    /// (one_optical_depth), half the bytes to scatter, the scatter being most of the grouping's time.
    void group_depths() {
        std::uint32_t* cursor = count_texels();
        if (grouped_depths_.size() < n_) grouped_depths_.resize(std::max(n_, grouped_depths_.size() + grouped_depths_.size() / 2));
        float* grouped = grouped_depths_.data();
        const std::uint32_t* where = where_.data();
        const float* depth = depth_.data();
        for (std::size_t i = 0; i < n_; ++i) grouped[cursor[where[i]]++] = depth[i];
    }

private:
    /// The grouping's first steps: texel k's count, then its fragments' offsets, in offsets_[k + 1]
    /// (offsets_[k + 2] once the scatter has moved each texel's cursor to its end). Returns the cursors.
    std::uint32_t* count_texels() {
        const std::size_t texels = std::size_t(width_) * std::size_t(rect_.y1 - rect_.y0);
        if (n_ > std::numeric_limits<std::uint32_t>::max()) throw argument_error("more than 2^32 fragments in one tile: use smaller tiles");
        offsets_.assign(texels + 2, 0);
        std::uint32_t* counts = offsets_.data() + 2;
        const std::uint32_t* where = where_.data();
        for (std::size_t i = 0; i < n_; ++i) ++counts[where[i]];
        for (std::size_t k = 2; k < offsets_.size(); ++k) offsets_[k] += offsets_[k - 1];
        return offsets_.data() + 1;
    }

#if HAIRSHADOW_AVX512_WALK
    /// The vector walk covers thin lines of one alpha (uniform attributes, a footprint constant in
    /// depth); other tiles walk in scalar.
    static bool simd_tile(const segment_bins& bins) noexcept { return one_optical_depth(bins); }
    /// The store's arrays, next slot and size, held in locals through the vector walk: its vector
    /// stores may alias anything, and through the members the compiler reloaded all of them after each.
    /// No optical depths: the vector walk's tiles keep one for the tile (tile_optical_depth()).
    struct store_cursor {
        std::uint32_t* where;
        float* depth;
        std::size_t n, end;
    };
    store_cursor cursor() noexcept { return {where_.data(), depth_.data(), n_, where_.size()}; }
    /// make_room for a cursor, which it renews where the store grows.
    void make_room(store_cursor& c, std::size_t extra) {
        if (c.n + extra <= c.end) return;
        n_ = c.n;
        make_room(extra);
        c = cursor();
    }
    friend struct avx512::tile_walk; ///< the AVX-512 walk (raster/detail/tile_walk_avx512.hpp), which fills the store through its cursor
#endif

    texel_rect rect_{};
    int width_ = 0;
    std::size_t n_ = 0;
    template <class T>
    using big_vector = std::vector<T, huge_page_allocator<T>>;
    big_vector<std::uint32_t> where_;            ///< each candidate's texel in the tile
    std::vector<std::uint32_t> offsets_;         ///< per texel counts, then offsets
    big_vector<float> depth_, optical_;          ///< each candidate's depth and b
    big_vector<optical_fragment> grouped_;
    big_vector<float> grouped_depths_;
    float last_alpha_ = -1.0f, last_optical_ = 0.0f;
    std::optional<float> tile_optical_;   ///< the last tile's one optical depth, where its walk kept no other
    std::vector<std::uint32_t> sorted_;   ///< the tile's segments by their steps (walk in any order)
    std::vector<std::uint16_t> steps_;    ///< each segment's steps in the tile
    std::vector<std::uint32_t> steps_of_; ///< per step count, the segments with it, then where they start
};

#if HAIRSHADOW_KERNEL_BODIES
HAIRSHADOW_DECL void tile_fragments::gather(const segment_bins& bins, std::size_t t, instruction_set instructions, fragment_order order) {
    rect_ = bins.tile_rect(t);
    width_ = rect_.x1 - rect_.x0;
    n_ = 0;
    tile_optical_.reset();
    const bool vector = instructions == instruction_set::avx512;
#if HAIRSHADOW_AVX512_WALK
    if (vector && simd_tile(bins)) {
        // Kept once: the segments the vector walk leaves to walk_segment_apart store the same b per fragment.
        tile_optical_ = optical_depth_cached(bins.uniform_shader().shade(0.0f).alpha);
        const bool gathered = bins.segment_count() < (std::size_t(1) << 28); // the records' word offsets fit the gathers
        if (order == fragment_order::any && gathered) avx512::tile_walk::walk_any_order_avx512(*this, bins, t);
        else avx512::tile_walk::walk_avx512(*this, bins, t);
    } else {
        walk_scalar(bins, t);
    }
#else
    (void)vector, (void)order;
    walk_scalar(bins, t);
#endif
}
#endif

} // namespace detail
} // namespace hairshadow
