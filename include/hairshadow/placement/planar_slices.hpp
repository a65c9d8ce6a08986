#pragma once
/// @file
/// Opacity shadow maps' planar slices (Kim & Neumann 2001, section 2): N maps at depths D_1..D_N
/// between the nearest fragment D_0 and the furthest, the same for every texel. A fragment adds to the
/// map of its slice and to every later one (each map holds the opacity in front of its depth); a query
/// interpolates linearly in depth between the maps that enclose it.

#include <hairshadow/placement/detail/slices_avx512.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
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
    /// Each texel's state depends on nothing of its fragments, in any order (order_free_maps).
    static constexpr bool fragment_order_free = true;
    static constexpr bool contiguous = true; ///< the slices tile [D_0, D_N) without gaps
    static constexpr std::string_view name = Spacing::name;
    static constexpr std::string_view glsl_name = "placement/planar_slices";
    /// The GLSL twin's configuration (gl/maps/policy_glsl.hpp); D_0 and D_N come from the map's extent.
    static std::string glsl_defines() {
        return std::string(Spacing::name == gamma_spacing::name ? "#define HS_GAMMA_SPACING\n" : "") + "#define HS_SLICE_FRACTION_BITS " +
               glsl_float_bits(fractions) + "\n";
    }
    /// i / N for i in [0, N], rounded once: where map i lies between D_0 and D_N before the spacing.
    static constexpr std::array<float, std::size_t(N) + 1> fractions = [] {
        std::array<float, std::size_t(N) + 1> f{};
        for (int i = 0; i <= N; ++i) f[std::size_t(i)] = float(i) / float(N);
        return f;
    }();
    struct texel_state {
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };

    /// Global pre-pass: D_0 is the nearest fragment, D_N just beyond the furthest.
    /// The same from the map's depth extent (the GL back end reduces it from its depth-range map).
    void prepare(const depth_extent& e) noexcept {
        near_ = e.nearest;
        far_ = detail::just_above(e.furthest);
        for (int i = 0; i < N; ++i) boundaries_[std::size_t(i)] = near_ + (far_ - near_) * Spacing::boundary(fractions[std::size_t(i)]);
        boundaries_[std::size_t(N)] = far_;
    }
    template <class Fragment>
    void prepare_texel(std::span<const Fragment>, texel_state&) const noexcept {}
    /// No per-texel state (per_pixel_depth::texel_state_from).
    void texel_state_from(float, float, texel_state&) const noexcept {}

    /// Depth of map i, i in [0, N] (D_0 .. D_N): D_0 + (D_N - D_0) spacing(i / N), computed once per build.
    float boundary(const texel_state&, int i) const noexcept { return boundaries_[std::size_t(std::clamp(i, 0, N))]; }
    /// The slice a fragment at `depth` falls in: D_k <= depth < D_{k+1}.
    int assign(const texel_state&, float depth) const noexcept { return std::min(reached(depth), N - 1); }
#if HAIRSHADOW_AVX512_WALK
    /// assign() for fragments of many texels, sixteen at a time (placement/detail/slices_avx512.hpp):
    /// by counting boundaries up to 16 maps, by bisection in registers from 17 to 64.
    HAIRSHADOW_AVX512_TARGET void assign_each_avx512(const texel_state*, std::span<const std::uint32_t> texels, std::span<const float> depths,
                                                     std::int32_t* layers) const noexcept
        requires(N <= 64)
    {
        if constexpr (N <= 16) detail::avx512::assign_planar_by_count<N>(boundaries_.data(), texels, depths, layers);
        else detail::avx512::assign_planar_by_bisection<N>(boundaries_.data(), texels, depths, layers);
    }
#endif
    layer_position locate(const texel_state&, float depth) const noexcept {
        if (!(depth >= near_)) return {-1, 0.0f};
        if (depth >= far_) return {N, 0.0f};
        const int k = reached(depth);
        return detail::position_in(k, depth, boundaries_[std::size_t(k)], boundaries_[std::size_t(k + 1)]);
    }
    /// Bytes of global state the maps need besides their texels (D_0 .. D_N, and D_0 and D_N apart).
    static constexpr std::size_t global_bytes() noexcept { return (std::size_t(N) + 3) * sizeof(float); }
    float nearest() const noexcept { return near_; }
    float furthest() const noexcept { return far_; }

private:
    /// How many of D_1..D_N lie at or before `depth` (0 for NaN): the k with D_k <= depth < D_k+1 where
    /// depth is in [D_0, D_N), since the boundaries never decrease. Without a branch for a few maps
    /// (the build calls this for every fragment), by bisection for many.
    int reached(float depth) const noexcept {
        if constexpr (N <= 16) {
            int k = 0;
            for (int i = 1; i <= N; ++i) k += int(boundaries_[std::size_t(i)] <= depth);
            return k;
        } else {
            if (!(depth >= near_)) return 0; // NaN too
            return int(std::upper_bound(boundaries_.begin() + 1, boundaries_.end(), depth) - (boundaries_.begin() + 1));
        }
    }

    float near_ = 0.0f, far_ = 0.0f;
    std::array<float, std::size_t(N) + 1> boundaries_{};
};

/// Uniformly spaced opacity maps (Kim & Neumann Fig. 3a).
template <int N>
using uniform_slices = planar_slices<N, uniform_spacing>;
/// Opacity maps spaced like gamma correction (Kim & Neumann Fig. 3c).
template <int N>
using gamma_slices = planar_slices<N, gamma_spacing>;

} // namespace hairshadow
