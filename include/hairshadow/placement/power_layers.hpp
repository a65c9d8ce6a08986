#pragma once
/// @file
/// Unreal Engine's deep shadow layers (HairStrands: HairStrandsDeepShadowCommon.ush, ComputeDOMWeights;
/// HairStrandsTransmittance.cpp, ComputeDeepShadowLayerDepths): a depth pass gives each texel the depth
/// z0 of its first fragment, and layer boundary k, for k = 1..K, lies at z0 + D (k / (K + 1))^e, with
/// e = 1 + 5.2 x the layer distribution (0.5 by default: e = 3.6) and D the hair's whole depth along
/// the light (Unreal's light frustum spans the hair group's bounds; here the map's extent). A fragment
/// adds to every boundary it is strictly in front of, so the stored layers are cumulative; fragments
/// behind the last boundary add to none. Queries move back by 0.05 x the first boundary (Unreal's
/// DepthBiasScale) before they are placed.

#include <hairshadow/config.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace hairshadow {

/// K layers from each texel's first fragment, their depths a power of their index (Unreal Engine's).
/// @tparam K number of layers (Unreal stores 4, one per channel of an RGBA16F texel)
template <int K>
class power_layers {
    static_assert(K >= 1 && K <= 8, "power_layers takes 1 to 8 layers");

public:
    static constexpr int layer_count = K;
    static constexpr bool cumulative = true;
    /// Each texel's state is its nearest fragment, whatever the order (order_free_maps).
    static constexpr bool fragment_order_free = true;
    static constexpr bool contiguous = true;
    static constexpr std::string_view name = "power_layers";
    static constexpr std::string_view glsl_name = "placement/power_layers";
    /// Unreal's r.HairStrands.DeepShadow.DepthBiasScale: queries move back by this share of the first boundary.
    static constexpr float depth_bias_scale = 0.05f;

    /// The depth map: the texel's first fragment.
    struct texel_state {
        float z0 = 0.0f;
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };

    /// Layers of Unreal's default distribution, 0.5.
    power_layers() : power_layers(0.5f) {}
    /// Layers of `distribution` in [0, 1] (Unreal's r.HairStrands.DeepShadow.LayerDistribution): 0 puts
    /// the boundaries at even steps of k / (K + 1), 1 crowds them towards the front (exponent 6.2).
    explicit power_layers(float distribution) : distribution_(distribution) {
        if (!(distribution >= 0.0f && distribution <= 1.0f)) throw argument_error("power_layers: the layer distribution must be in [0, 1]");
        const double exponent = 1.0 + 5.2 * double(distribution);
        for (int k = 1; k <= K; ++k) fractions_[std::size_t(k)] = float(std::pow(double(k) / double(K + 1), exponent));
    }

    /// Boundary k's depth behind z0, in units of the hair's depth D: (k / (K + 1))^e; 0 for k = 0.
    float fraction(int k) const noexcept { return fractions_[std::size_t(k)]; }
    float distribution() const noexcept { return distribution_; }

    /// The boundaries from the map's extent (the GL twin computes the same floats from its own).
    void prepare(const depth_extent& e) noexcept {
        const float depth = std::max(e.furthest - e.nearest, 1e-6f);
        for (int k = 0; k <= K; ++k) boundaries_[std::size_t(k)] = detail::rounded(depth * fractions_[std::size_t(k)]);
        bias_ = detail::rounded(depth_bias_scale * boundaries_[1]);
    }
    /// The depth pass: z0 is the nearest fragment.
    template <class Fragment>
    void prepare_texel(std::span<const Fragment> fragments, texel_state& s) const noexcept {
        if (!fragments.empty()) s.z0 = detail::texel_extent_of(fragments).nearest;
    }
    void texel_state_from(float nearest, float, texel_state& s) const noexcept { s.z0 = nearest; }

    /// The layer a fragment starts adding to: the boundaries it is not in front of; -1 behind the last.
    int assign(const texel_state& s, float depth) const noexcept {
        const float behind = depth - s.z0;
        int k = 0;
        for (int i = 1; i <= K; ++i) k += int(behind >= boundaries_[std::size_t(i)]);
        return k == K ? -1 : k;
    }
    /// A query's place: in front of z0 nothing lies in front of it; otherwise its depth behind z0,
    /// less the bias (at least 0), among the boundaries.
    layer_position locate(const texel_state& s, float depth) const noexcept {
        const float behind = depth - s.z0;
        if (!(behind >= 0.0f)) return {-1, 0.0f};
        const float d = std::max(behind - bias_, 0.0f);
        if (d >= boundaries_[std::size_t(K)]) return {K, 0.0f};
        int k = 0;
        for (int i = 1; i < K; ++i) k += int(d >= boundaries_[std::size_t(i)]);
        return detail::position_in(k, d, boundaries_[std::size_t(k)], boundaries_[std::size_t(k + 1)]);
    }
    static constexpr std::size_t global_bytes() noexcept { return sizeof(float) * std::size_t(K + 1); }

    /// The GLSL twin's uniforms (gl/maps/policy_glsl.hpp): the boundaries' fractions, as the CPU rounded them.
    template <class Set>
    void glsl_uniforms(Set&& set) const {
        for (int k = 1; k <= K; ++k) set("hs_power_fraction", fractions_[std::size_t(k)], k); // element k of the array
    }

private:
    float distribution_;
    std::array<float, std::size_t(K) + 1> fractions_{};
    std::array<float, std::size_t(K) + 1> boundaries_{};
    float bias_ = 0.0f;
};

} // namespace hairshadow
