#pragma once
/// @file
/// Light-space fragments and the per-texel buffer that holds them.

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace hairshadow {

class rasterizer;

/// One fragment of a strand in a light-space texel: linear depth in [0, 1] and alpha in [0, 1).
struct fragment {
    float depth;
    float alpha;
    friend bool operator==(const fragment&, const fragment&) = default;
};

/// A fragment's optical depth b = -ln(1 - alpha): what it adds to the optical depth behind it. Every
/// method sums it from this one function, so a fragment's b is the same in every build path.
inline float optical_depth_of(float alpha) noexcept { return -std::log1p(-alpha); }

/// A fragment whose optical depth is already known: what the tiled build keeps per fragment, having
/// computed b once per segment wherever the segment's alpha is constant.
struct optical_fragment {
    float depth;
    float optical_depth; ///< optical_depth_of(alpha)
    friend bool operator==(const optical_fragment&, const optical_fragment&) = default;
};

/// The optical depth of either kind of fragment; the policies read fragments through this.
inline float fragment_optical_depth(const fragment& f) noexcept { return optical_depth_of(f.alpha); }
inline float fragment_optical_depth(const optical_fragment& f) noexcept { return f.optical_depth; }

/// Every texel's fragments, stored texel after texel (row-major, y then x). Within a texel, fragments
/// keep the order of the segments that produced them, whatever the thread count.
class fragment_buffer {
public:
    fragment_buffer() = default;
    fragment_buffer(int resolution, std::vector<std::uint64_t> offsets, std::vector<fragment> fragments)
        : resolution_(resolution), offsets_(std::move(offsets)), fragments_(std::move(fragments)) {}

    int resolution() const noexcept { return resolution_; }
    std::size_t texel_count() const noexcept { return std::size_t(resolution_) * std::size_t(resolution_); }
    std::size_t size() const noexcept { return fragments_.size(); }
    /// The fragments of texel (x, y).
    std::span<const fragment> texel(int x, int y) const noexcept { return texel(std::size_t(y) * std::size_t(resolution_) + std::size_t(x)); }
    /// The fragments of the texel with row-major index i.
    std::span<const fragment> texel(std::size_t i) const noexcept {
        return {fragments_.data() + offsets_[i], static_cast<std::size_t>(offsets_[i + 1] - offsets_[i])};
    }
    const std::vector<std::uint64_t>& offsets() const noexcept { return offsets_; }
    const std::vector<fragment>& fragments() const noexcept { return fragments_; }
    friend bool operator==(const fragment_buffer&, const fragment_buffer&) = default;

private:
    friend class rasterizer; // refills the vectors in place, reusing their memory
    int resolution_ = 0;
    std::vector<std::uint64_t> offsets_{0};
    std::vector<fragment> fragments_;
};

} // namespace hairshadow
