#pragma once
/// @file
/// Opacity shadow maps' planar slices (Kim & Neumann 2001, section 2): N maps at depths D_1..D_N
/// between the nearest fragment D_0 and the furthest, the same for every texel. A fragment adds to the
/// map of its slice and to every later one (each map holds the opacity in front of its depth); a query
/// interpolates linearly in depth between the maps that enclose it.

#include <hairshadow/placement/layer_position.hpp>

#include <cmath>
#include <cstddef>
#include <span>
#include <string_view>

namespace hairshadow {

/// Slices of equal thickness (Kim & Neumann Fig. 3a).
struct uniform_spacing {
    static constexpr std::string_view name = "uniform";
    static constexpr float boundary(float t) noexcept { return t; }
    static float inverse(float u) noexcept { return u; }
};

/// Slices growing with depth, denser near the light, "analogous to gamma correction" (Kim & Neumann
/// Fig. 3c). The paper gives no formula; we use D_i = D_0 + (D_N - D_0) (i / N)^2.
struct gamma_spacing {
    static constexpr std::string_view name = "gamma";
    static constexpr float gamma = 2.0f;
    static constexpr float boundary(float t) noexcept { return t * t; }
    static float inverse(float u) noexcept { return std::sqrt(u); }
};

/// N planar slices between the nearest and furthest fragment of the whole map.
/// @tparam N number of opacity maps
/// @tparam Spacing uniform_spacing or gamma_spacing
template <int N, class Spacing = uniform_spacing>
class planar_slices {
    static_assert(N >= 1, "planar_slices needs at least one slice");

public:
    static constexpr int layer_count = N;
    static constexpr bool cumulative = true; ///< each map holds the opacity in front of its depth
    static constexpr bool contiguous = true; ///< the slices tile [D_0, D_N) without gaps
    static constexpr std::string_view name = Spacing::name;
    static constexpr std::string_view glsl_name = "placement/planar_slices";
    struct texel_state {
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };

    /// Global pre-pass: D_0 is the nearest fragment, D_N just beyond the furthest.
    void prepare(const fragment_buffer& fragments) noexcept { prepare(extent_of(fragments)); }
    /// The same from the map's depth extent (the GL back end reduces it from its depth-range map).
    void prepare(const depth_extent& e) noexcept {
        near_ = e.nearest;
        far_ = detail::just_above(e.furthest);
    }
    template <class Fragment>
    void prepare_texel(std::span<const Fragment>, texel_state&) const noexcept {}

    /// Depth of map i, i in [0, N] (D_0 .. D_N).
    float boundary(const texel_state&, int i) const noexcept {
        return i >= N ? far_ : near_ + (far_ - near_) * Spacing::boundary(float(i) / float(N));
    }
    /// The slice a fragment at `depth` falls in: D_k <= depth < D_{k+1}.
    int assign(const texel_state& s, float depth) const noexcept {
        const int k = locate(s, depth).index;
        return std::clamp(k, 0, N - 1);
    }
    layer_position locate(const texel_state& s, float depth) const noexcept {
        if (!(depth >= near_)) return {-1, 0.0f};
        if (depth >= far_) return {N, 0.0f};
        const int k = detail::settle_layer(Spacing::inverse((depth - near_) / (far_ - near_)) * float(N), N - 1, depth,
                                           [&](int i) { return boundary(s, i); });
        return detail::position_in(k, depth, boundary(s, k), boundary(s, k + 1));
    }
    /// Bytes of global state the maps need besides their texels (D_0 and D_N).
    static constexpr std::size_t global_bytes() noexcept { return 2 * sizeof(float); }
    float nearest() const noexcept { return near_; }
    float furthest() const noexcept { return far_; }

private:
    float near_ = 0.0f, far_ = 0.0f;
};

/// Uniformly spaced opacity maps (Kim & Neumann Fig. 3a).
template <int N>
using uniform_slices = planar_slices<N, uniform_spacing>;
/// Opacity maps spaced like gamma correction (Kim & Neumann Fig. 3c).
template <int N>
using gamma_slices = planar_slices<N, gamma_spacing>;

} // namespace hairshadow
