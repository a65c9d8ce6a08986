#pragma once
/// @file
/// Occupancy maps' per-texel depth range (Sintorn & Assarsson 2009, section 3.1): the nearest and
/// furthest fragment of each texel bound S equal slices, so that every slice lies inside the hair.

#include <hairshadow/config.hpp>
#include <hairshadow/placement/detail/slices_avx512.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace hairshadow {

/// S slices between each texel's nearest and furthest fragment.
/// @tparam S number of slices (128 in the paper)
template <int S>
class depth_range {
    static_assert(S >= 1, "depth_range needs at least one slice");

public:
    static constexpr int layer_count = S;
    static constexpr bool cumulative = true; ///< read as opacity slices when interpolated
    /// Each texel's state depends on its fragments' depths as a set (nearest and furthest), not their
    /// order (order_free_maps).
    static constexpr bool fragment_order_free = true;
    static constexpr bool contiguous = true;
    static constexpr std::string_view name = "depth_range";
    static constexpr std::string_view glsl_name = "placement/depth_range";
    /// The depth-range map (MIN / MAX blending on GL).
    struct texel_state {
        float nearest = 0.0f;
        float furthest = 0.0f;
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };

    void prepare(const depth_extent&) const noexcept {}
    template <class Fragment>
    void prepare_texel(std::span<const Fragment> fragments, texel_state& s) const noexcept {
        if (fragments.empty()) return;
        const auto range = detail::texel_extent_of(fragments);
        texel_state_from(range.nearest, range.furthest, s);
    }
    /// The texel's state from its nearest and furthest fragment (per_pixel_depth::texel_state_from).
    void texel_state_from(float nearest, float furthest, texel_state& s) const noexcept { s.nearest = nearest, s.furthest = furthest; }
    /// Depth of slice boundary k in [0, S] (never a fused multiply-add, so that every build, and
    /// assign_each_avx512, places a boundary on the same float).
    float boundary(const texel_state& s, int k) const noexcept {
        return s.nearest + detail::rounded((s.furthest - s.nearest) * (float(k) / float(S)));
    }
    /// The slice floor(S (z - near) / (far - near)) of the paper, the furthest fragment in the last.
    int assign(const texel_state& s, float depth) const noexcept {
        if (!(s.furthest > s.nearest)) return 0;
        return std::clamp(slice_of(s, depth), 0, S - 1);
    }
#if HAIRSHADOW_AVX512_WALK
    /// assign() for fragments of many texels, sixteen at a time (placement/detail/slices_avx512.hpp).
    HAIRSHADOW_AVX512_TARGET void assign_each_avx512(const texel_state* states, std::span<const std::uint32_t> texels,
                                                     std::span<const float> depths, std::int32_t* layers) const noexcept {
        static_assert(sizeof(texel_state) == 2 * sizeof(float) && offsetof(texel_state, furthest) == sizeof(float));
        detail::avx512::assign_depth_range<S>(reinterpret_cast<const float*>(states), texels, depths, layers);
    }
#endif
    layer_position locate(const texel_state& s, float depth) const noexcept {
        if (!(s.furthest > s.nearest)) return depth > s.nearest ? layer_position{S, 0.0f} : layer_position{-1, 0.0f};
        if (!(depth >= s.nearest)) return {-1, 0.0f};
        const int k = slice_of(s, depth);
        if (k >= S) return {S, 0.0f};
        return detail::position_in(k, depth, boundary(s, k), boundary(s, k + 1));
    }
    static constexpr std::size_t global_bytes() noexcept { return 0; }

private:
    /// The k with boundary(k) <= depth < boundary(k + 1), or S past the furthest boundary, settled
    /// against the boundaries so that slab boundaries are exact.
    int slice_of(const texel_state& s, float depth) const noexcept {
        return detail::settle_layer((depth - s.nearest) / (s.furthest - s.nearest) * float(S), S, depth,
                                    [&](int i) { return boundary(s, i); });
    }
};

} // namespace hairshadow
