#pragma once
/// @file
/// Reconstruction by an assumed fibre density: approximate deep shadow maps, as AMD TressFX ships them
/// (TressFXLighting.hlsl, ComputeShadowAttenuation). A texel keeps only its first fragment's depth z0
/// (per_pixel_depth's depth map); a point d world units behind it lies behind
/// n = d / (fibre spacing x fibre radius) fibres, at least one once d > 1e-5, and T = (1 - alpha)^n.
/// TressFX counts every fibre: its settings hold m_HairMaxShadowFibers = 50 and upload it, but
/// ComputeShadowAttenuation never reads it, so no cap is the default here; a cap is an option
/// (fibre_density_parameters::max_fibres). The measured variant takes the density from the texel's own
/// fragments instead: their count over their depth span (depth_range's nearest and furthest).

#include <hairshadow/core/detail/tail_bytes.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/raster/fragment.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace hairshadow {

/// Where the fibre density comes from.
enum class fibre_density_source {
    fixed,    ///< the parameters' constant density, TressFX's model
    measured, ///< each texel's fragment count over its depth span, with the fragments' mean opacity
};

/// TressFX's hair shadow parameters (TressFXSettings.h defaults), in the model's world units.
struct fibre_density_parameters {
    float spacing = 0.4f;    ///< fibre spacing, in fibre radii
    float radius = 0.0021f;  ///< fibre radius, world units
    float alpha = 0.35f;     ///< opacity of one fibre
    /// Fibres counted at most: a whole number, or infinity for none (TressFX's shader counts them all;
    /// its unread m_HairMaxShadowFibers is 50).
    float max_fibres = std::numeric_limits<float>::infinity();

    /// World depth per fibre along the light.
    float fibre_step() const noexcept { return spacing * radius; }
    /// -ln(1 - alpha): one fibre's optical depth.
    float fibre_optical_depth() const noexcept { return -std::log1p(-alpha); }
    /// Throws argument_error unless spacing and radius are positive and finite, alpha is in (0, 1)
    /// and the cap is infinite or a whole number of fibres, at least one.
    void check() const {
        const auto positive = [](float v) { return std::isfinite(v) && v > 0.0f; };
        if (!positive(spacing) || !positive(radius) || !positive(fibre_step()))
            throw argument_error("fibre density: spacing and radius must be positive and finite, and so must their product");
        if (!(alpha > 0.0f && alpha < 1.0f)) throw argument_error("fibre density: the fibre alpha must be in (0, 1)");
        if (!(max_fibres >= 1.0f && (std::isinf(max_fibres) || max_fibres == std::floor(max_fibres))))
            throw argument_error("fibre density: the cap must be a whole number of fibres, at least one, or none");
    }
    friend bool operator==(const fibre_density_parameters&, const fibre_density_parameters&) = default;
};

namespace detail {
/// A point this little behind the first fragment is still on it: TressFX's 1e-5 world units, and at
/// least four float steps of a linear depth near 1, so that rounding never puts a point on the first
/// fibre behind it (CPU and GL compute depths in their own order).
inline constexpr float on_first_fibre = 1e-5f;
inline constexpr float on_first_fibre_depth = 2.5e-7f;

template <class P>
concept first_fragment_state = requires(const typename P::texel_state& s) { s.z0; } || requires(const typename P::texel_state& s) { s.nearest; };
template <class P>
concept fragment_span_state = requires(const typename P::texel_state& s) {
    s.nearest;
    s.furthest;
};
} // namespace detail

/// Optical depth from an assumed density of fibres behind each texel's first fragment.
/// @tparam Source the parameters' constant density (TressFX) or each texel's measured one
template <fibre_density_source Source = fibre_density_source::fixed>
class fibre_density {
public:
    static constexpr std::string_view name = "fibre_density";
    static constexpr std::string_view glsl_name = "reconstruction/fibre_density";

    /// The fixed density needs the first fragment (per_pixel_depth's z0 or depth_range's nearest); the
    /// measured one also the last (depth_range).
    template <class Placement>
    static constexpr bool accepts =
        Source == fibre_density_source::fixed ? detail::first_fragment_state<Placement> : detail::fragment_span_state<Placement>;

    struct covered {
        bool any = false; ///< the texel has a fragment (else it casts no shadow)
        friend bool operator==(const covered&, const covered&) = default;
    };
    template <class Accumulation>
    struct measured {
        typename Accumulation::value_type optical_depth{}; ///< sum of the fragments' b
        /// An 8-bit sum's padding before the count, named (maps_hash reads a texel's bytes)
        [[no_unique_address]] detail::tail_bytes<(4 - sizeof(typename Accumulation::value_type) % 4) % 4, measured> pad{};
        std::uint32_t fragments = 0;
        friend bool operator==(const measured&, const measured&) = default;
    };
    /// Fixed density: only whether the texel is covered; measured: the texel's fragments summed.
    template <class Placement, class Accumulation>
    using storage = std::conditional_t<Source == fibre_density_source::fixed, covered, measured<Accumulation>>;

    explicit fibre_density(fibre_density_parameters parameters = {}) : parameters_(parameters) { parameters_.check(); }

    /// The light's world depth per unit of linear depth, which turns depths into fibre counts.
    void prepare(const light_space& light) noexcept { depth_scale_ = light.far_plane() - light.near_plane(); }

    template <class Placement, class Accumulation, class Fragment>
    static void build(const Placement&, const typename Placement::texel_state&, std::span<const Fragment> fragments,
                      storage<Placement, Accumulation>& out) {
        if constexpr (Source == fibre_density_source::fixed) {
            out.any = !fragments.empty();
        } else {
            typename Accumulation::sum_type sum{};
            for (const auto& f : fragments) sum = Accumulation::add(sum, fragment_optical_depth(f));
            out.optical_depth = Accumulation::store(sum);
            out.fragments = std::uint32_t(fragments.size());
        }
    }

    /// Fibres in front of linear depth `depth`, and the optical depth each one has.
    template <class Placement, class Accumulation>
    float optical_depth(const Placement& placement, const typename Placement::texel_state& state, const storage<Placement, Accumulation>& in,
                        float depth) const noexcept {
        const float z0 = placement.boundary(state, 0); // the first fragment
        const float behind = (depth - z0) * depth_scale_;  // world units behind it
        if (!(behind > detail::on_first_fibre) || !(depth - z0 > detail::on_first_fibre_depth)) return 0.0f;
        if constexpr (Source == fibre_density_source::fixed) {
            if (!in.any) return 0.0f;
            const float fibres = std::clamp(behind / parameters_.fibre_step(), 1.0f, parameters_.max_fibres);
            return fibres * parameters_.fibre_optical_depth();
        } else {
            if (in.fragments == 0) return 0.0f;
            // n fragments over the span from first to last: n - 1 gaps, so the k-th fragment behind the
            // first is reached at k gaps and a point on it has k fibres in front, as the exact map says
            // for evenly spaced fragments; behind the last all n are in front.
            const float count = float(in.fragments);
            const float span = state.furthest - state.nearest;
            const float fibres = span > 0.0f && depth <= state.furthest ? std::clamp((depth - z0) / span * (count - 1.0f), 1.0f, count) : count;
            return fibres * (Accumulation::decode(in.optical_depth) / count);
        }
    }

    /// Maps a texel stores, for inspection: none for the fixed density, the texel's summed optical
    /// depth for the measured one.
    template <class Placement>
    static constexpr int stored_maps = Source == fibre_density_source::fixed ? 0 : 1;
    template <class Placement, class Accumulation>
    static float stored_optical_depth(const storage<Placement, Accumulation>& in, int) noexcept {
        if constexpr (Source == fibre_density_source::fixed) return 0.0f;
        else return Accumulation::decode(in.optical_depth);
    }

    const fibre_density_parameters& parameters() const noexcept { return parameters_; }
    /// World units per unit of linear depth, from the last prepare().
    float depth_scale() const noexcept { return depth_scale_; }

private:
    fibre_density_parameters parameters_;
    float depth_scale_ = 1.0f;
};

} // namespace hairshadow
