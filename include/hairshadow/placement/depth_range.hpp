#pragma once
/// @file
/// Occupancy maps' per-texel depth range (Sintorn & Assarsson 2009, section 3.1): the nearest and
/// furthest fragment of each texel bound S equal slices, so that every slice lies inside the hair.

#include <hairshadow/config.hpp>
#include <hairshadow/placement/detail/assign_each.hpp>
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
    /// assign() for fragment i of a tile, layers[i] = assign(states[texels[i]], depths[i]), sixteen at
    /// a time (placement/detail/assign_each.hpp): the same estimate, settled against the same boundaries,
    /// lane by lane, one step at a time while any lane still moves.
    HAIRSHADOW_AVX512_TARGET void assign_each_avx512(const texel_state* states, std::span<const std::uint32_t> texels,
                                                     std::span<const float> depths, std::int32_t* layers) const noexcept {
        static_assert(sizeof(texel_state) == 2 * sizeof(float) && offsetof(texel_state, furthest) == sizeof(float));
        const float* ranges = reinterpret_cast<const float*>(states);
        const __m512 slices = _mm512_set1_ps(float(S));
        for (std::size_t i = 0; i < texels.size(); i += 16) {
            const __mmask16 lanes = detail::avx512::first_lanes(texels.size() - i);
            const __m512i texel = _mm512_maskz_loadu_epi32(lanes, texels.data() + i);
            const __m512 depth = _mm512_maskz_loadu_ps(lanes, depths.data() + i);
            const __m512 nearest = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, texel, ranges, 8);
            const __m512 furthest = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, texel, ranges + 1, 8);
            const __m512 span = _mm512_sub_ps(furthest, nearest);
            const __mmask16 ranged = _mm512_mask_cmp_ps_mask(lanes, furthest, nearest, _CMP_GT_OQ); // else slice 0
            // settle_layer: the estimate's whole part (0 for NaN and negatives), then down and up.
            const __m512 estimate = _mm512_mul_ps(_mm512_div_ps(_mm512_sub_ps(depth, nearest), span), slices);
            const __mmask16 positive = _mm512_mask_cmp_ps_mask(ranged, estimate, _mm512_setzero_ps(), _CMP_GT_OQ);
            __m512i k = _mm512_maskz_cvttps_epi32(positive, _mm512_min_ps(estimate, slices));
            k = detail::avx512::settle_layers(k, depth, ranged, S, [=](__m512i j, __mmask16) HAIRSHADOW_AVX512_TARGET {
                return boundary_avx512(nearest, span, j);
            });
            k = _mm512_min_epi32(k, _mm512_set1_epi32(S - 1)); // never negative: it starts at 0 or above and stops there
            _mm512_mask_storeu_epi32(layers + i, lanes, k);
        }
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
#if HAIRSHADOW_AVX512_WALK
    /// boundary(k) for each lane's texel (nearest, and span = furthest - nearest) and k.
    HAIRSHADOW_AVX512_TARGET static __m512 boundary_avx512(__m512 nearest, __m512 span, __m512i k) noexcept {
        const __m512 fraction = _mm512_div_ps(_mm512_cvtepi32_ps(k), _mm512_set1_ps(float(S)));
        return _mm512_add_ps(nearest, detail::avx512::rounded(_mm512_mul_ps(span, fraction)));
    }
#endif
    /// The k with boundary(k) <= depth < boundary(k + 1), or S past the furthest boundary, settled
    /// against the boundaries so that slab boundaries are exact.
    int slice_of(const texel_state& s, float depth) const noexcept {
        return detail::settle_layer((depth - s.nearest) / (s.furthest - s.nearest) * float(S), S, depth,
                                    [&](int i) { return boundary(s, i); });
    }
};

} // namespace hairshadow
