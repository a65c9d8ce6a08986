#pragma once
/// @file
/// Light-space fragments and the per-texel buffer that holds them.

#include <hairshadow/config.hpp>

#include <bit>
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
/// method sums it from this one function, so a fragment's b is the same in every build path, the
/// GPU's compute build included: it uses only float operations that IEEE rounds exactly (no fused
/// multiply-adds, see rounded()), mirrored in shaders/compute/common.glsl, so both give the same bits.
/// Within 3e-7 relative of -log1p(-alpha) for alpha in [0, 1); other values (which no rasteriser
/// makes) go to std::log1p.
inline float optical_depth_of(float alpha) noexcept {
    using detail::rounded;
    if (alpha >= 0.0f && alpha < 0.5f) {
        // -ln(1 - a) = 2 atanh(s), s = a / (2 - a) <= 1/3: 2 s (1 + s^2/3 + s^4/5 + ... + s^14/15),
        // whose first term left out is below 2e-8 of the sum. 1 - a itself would lose a's low bits.
        const float s = alpha / (2.0f - alpha), s2 = rounded(s * s);
        float p = 1.0f / 15.0f;
        for (const float c : {1.0f / 13.0f, 1.0f / 11.0f, 1.0f / 9.0f, 1.0f / 7.0f, 1.0f / 5.0f, 1.0f / 3.0f, 1.0f}) p = c + rounded(s2 * p);
        return rounded(2.0f * s) * p;
    }
    if (alpha >= 0.5f && alpha < 1.0f) {
        // u = 1 - a, exact here, is m 2^e with m in [sqrt(1/2), sqrt(2)): ln u = e ln 2 + 2 atanh(s),
        // s = (m - 1) / (m + 1), |s| <= 0.172, five terms of the series.
        const float u = 1.0f - alpha;
        const std::uint32_t bits = std::bit_cast<std::uint32_t>(u);
        int e = int((bits >> 23) & 0xffu) - 127;
        float m = std::bit_cast<float>((bits & 0x7fffffu) | 0x3f800000u);
        if (m > 1.41421356f) m *= 0.5f, ++e;
        const float s = (m - 1.0f) / (m + 1.0f), s2 = rounded(s * s);
        float p = 1.0f / 11.0f;
        for (const float c : {1.0f / 9.0f, 1.0f / 7.0f, 1.0f / 5.0f, 1.0f / 3.0f, 1.0f}) p = c + rounded(s2 * p);
        const float ln_u = rounded(float(e) * 0.693147182f) + rounded(rounded(2.0f * s) * p);
        return -ln_u;
    }
    return -std::log1p(-alpha);
}

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
