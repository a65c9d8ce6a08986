#pragma once
/// @file
/// Per-texel lists stored tile by tile: each square tile of the map owns one block, so a tile built
/// from its fragments is written once, whole, without knowing any other tile's size. The exact and
/// compressed deep shadow maps keep their texels' functions here.

#include <hairshadow/core/error.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace hairshadow::detail {

/// The square tiles of a map: tile t covers texels [x0, x1) x [y0, y1), row-major.
struct map_tiling {
    int resolution = 0;
    int tile = 64;
    int tiles_x = 0;

    map_tiling() = default;
    /// Throws argument_error for a tile size below 1 (the streamed builds check raster_options first).
    map_tiling(int res, int tile_size) : resolution(res), tile(positive(tile_size)), tiles_x(int((res + (long long)tile_size - 1) / tile_size)) {}

    static int positive(int tile_size) {
        if (tile_size < 1) throw argument_error("tile size must be at least 1");
        return tile_size;
    }

    std::size_t tile_count() const noexcept { return std::size_t(tiles_x) * std::size_t(tiles_x); }
    std::size_t tile_of(int x, int y) const noexcept { return std::size_t(y / tile) * std::size_t(tiles_x) + std::size_t(x / tile); }
    int x0(std::size_t t) const noexcept { return int(t % std::size_t(tiles_x)) * tile; }
    int y0(std::size_t t) const noexcept { return int(t / std::size_t(tiles_x)) * tile; }
    int width(std::size_t t) const noexcept { return std::min(resolution, x0(t) + tile) - x0(t); }
    int height(std::size_t t) const noexcept { return std::min(resolution, y0(t) + tile) - y0(t); }
};

/// `Arrays` parallel lists per texel (the exact map: depths and optical depths), of T. Tile t's block
/// holds its texels' lists one after another, each array in turn: array k of a tile with n entries
/// starts at k n. A texel keeps where its list starts in its tile's block and how long it is.
template <class T, std::size_t Arrays = 1>
class tile_lists {
public:
    tile_lists() = default;
    explicit tile_lists(const map_tiling& tiling)
        : tiling_(tiling), begin_(std::size_t(tiling.resolution) * std::size_t(tiling.resolution)), count_(begin_.size()), blocks_(tiling.tile_count()) {}

    const map_tiling& tiling() const noexcept { return tiling_; }

    /// Array k of texel (x, y)'s list.
    std::span<const T> list(int x, int y, std::size_t k = 0) const noexcept {
        const std::size_t texel = std::size_t(y) * std::size_t(tiling_.resolution) + std::size_t(x);
        const std::vector<T>& block = blocks_[tiling_.tile_of(x, y)];
        return {block.data() + k * (block.size() / Arrays) + begin_[texel], count_[texel]};
    }

    /// Writes tile t's block: `lengths[i]` entries for the tile's i-th texel (row-major within the
    /// tile), then fill(block, n) writes them, array k of texel i at k n + (the lengths before i).
    /// Throws argument_error where a tile would hold more than 2^32 - 1 entries an array.
    template <class Lengths, class Fill>
    void write_tile(std::size_t t, const Lengths& lengths, Fill&& fill) {
        const int x0 = tiling_.x0(t), y0 = tiling_.y0(t), w = tiling_.width(t), h = tiling_.height(t);
        std::uint64_t n = 0;
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const std::size_t texel = std::size_t(y0 + j) * std::size_t(tiling_.resolution) + std::size_t(x0 + i);
                const std::uint64_t length = lengths[std::size_t(j) * std::size_t(w) + std::size_t(i)];
                if (n + length > std::numeric_limits<std::uint32_t>::max())
                    throw argument_error("one tile of the deep shadow map would hold more than 2^32 entries; use a smaller tile size");
                begin_[texel] = std::uint32_t(n), count_[texel] = std::uint32_t(length);
                n += length;
            }
        std::vector<T> block(std::size_t(n) * Arrays);
        fill(block, std::size_t(n));
        blocks_[t] = std::move(block); // tiles are written by several threads at once, each its own

    }

    /// Entries an array, in all.
    std::size_t size() const noexcept {
        std::size_t n = 0;
        for (const auto& block : blocks_) n += block.size() / Arrays;
        return n;
    }
    std::size_t memory_bytes() const noexcept {
        return (begin_.size() + count_.size()) * sizeof(std::uint32_t) + blocks_.size() * sizeof(std::vector<T>) + size() * Arrays * sizeof(T);
    }

private:
    map_tiling tiling_;
    std::vector<std::uint32_t> begin_, count_;
    std::vector<std::vector<T>> blocks_;
};

} // namespace hairshadow::detail
