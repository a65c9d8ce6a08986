#pragma once
/// @file
/// A depth extent: the nearest and furthest fragment depth, of a whole buffer (a global pre-pass)
/// or of one texel's fragments. "Extent" always means these two depths; "depth range" is the
/// placement that spreads its layers over the scene's extent (placement/depth_range.hpp).

#include <hairshadow/raster/fragment.hpp>

#include <algorithm>
#include <limits>
#include <span>

namespace hairshadow {

/// Nearest and furthest fragment depth; {0, 0} for an empty buffer.
struct depth_extent {
    float nearest = 0.0f;
    float furthest = 0.0f;
};

inline depth_extent extent_of(const fragment_buffer& fragments) noexcept {
    if (fragments.size() == 0) return {};
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const auto& f : fragments.fragments()) {
        lo = std::min(lo, f.depth);
        hi = std::max(hi, f.depth);
    }
    return {lo, hi};
}

namespace detail {
/// Widens an extent by one more fragment's depth (started at the first fragment's).
inline void widen_extent(depth_extent& extent, float depth) noexcept {
    extent.nearest = std::min(extent.nearest, depth);
    extent.furthest = std::max(extent.furthest, depth);
}

/// A fragment's depth, where a texel holds fragments, or their depths alone (a texel whose fragments
/// share one optical depth: tile_fragments::group_depths).
template <class Fragment>
float depth_of(const Fragment& f) noexcept {
    return f.depth;
}
inline float depth_of(float depth) noexcept { return depth; }

/// The extent of a texel's fragments, reduced in their order from the first: the order matters
/// only for the sign of a zero, and widen_extent keeps the same order.
template <class Fragment>
depth_extent texel_extent_of(std::span<const Fragment> fragments) noexcept {
    depth_extent extent{depth_of(fragments[0]), depth_of(fragments[0])};
    for (const auto& f : fragments) widen_extent(extent, depth_of(f));
    return extent;
}
} // namespace detail

} // namespace hairshadow
