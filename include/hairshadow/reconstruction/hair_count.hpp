#pragma once
/// @file
/// Reconstruction by hair count, as Unreal Engine's HairStrands deep shadows
/// (HairStrandsDeepTransmittanceCommon.ush, ComputeTransmittanceFromHairCount): the count of hairs in
/// front of a point, interpolated linearly between the layers, gives T = A^max(0, count - 1), A being
/// the transmittance of one hair; the "- 1" removes a hair's shadow on itself.
///
/// Unreal counts each fragment by its coverage of the texel and reads A from its fibre-scattering
/// table. Here a fragment's alpha already is its opacity times its coverage (raster/fragment.hpp), so
/// one hair is a fragment of alpha `hair_alpha` (A = 1 - hair_alpha), and the count is the optical
/// depth in front of the point over that hair's: count = tau / b, b = -ln(1 - hair_alpha), and
/// T = exp(-max(0, tau - b)). The layers therefore hold optical depth, as interpolation's do (the same
/// build, accumulations and fast paths), and only the look-up differs. Where every fragment has the
/// hair's alpha, the count is the number of fragments; with the "- 1" left out (`minus_one` false),
/// T is interpolation's. docs/methods.md measures both against the exact map.

#include <hairshadow/core/error.hpp>
#include <hairshadow/reconstruction/interpolation.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

namespace hairshadow {

/// What one hair is, for hair_count.
struct hair_count_parameters {
    /// The alpha of one hair's fragment in the map (its opacity times its coverage of a texel): the
    /// three test models' fragments at 512x512 have 0.105 (Ratboy), 0.117 (Sintel) and 0.129 (curly).
    float hair_alpha = 0.12f;
    /// Unreal's "- 1": the hair the point lies on casts no shadow on it.
    bool minus_one = true;

    /// -ln(1 - hair_alpha): one hair's optical depth, in double rounded once to float, so that a value
    /// the compiler folds and one the C library computes at run time agree.
    float hair_optical_depth() const noexcept { return float(-std::log1p(-double(hair_alpha))); }
    /// Throws argument_error unless hair_alpha is in (0, 1).
    void check() const {
        if (!(hair_alpha > 0.0f && hair_alpha < 1.0f)) throw argument_error("hair count: the hair alpha must be in (0, 1)");
    }
    friend bool operator==(const hair_count_parameters&, const hair_count_parameters&) = default;
};

/// Interpolated optical depth, less one hair's (Unreal Engine's hair count).
class hair_count : public interpolation {
public:
    static constexpr std::string_view name = "hair_count";
    static constexpr std::string_view glsl_name = "reconstruction/hair_count";

    hair_count() = default;
    explicit hair_count(const hair_count_parameters& parameters) : parameters_(parameters), hair_(parameters.hair_optical_depth()) { parameters.check(); }
    const hair_count_parameters& parameters() const noexcept { return parameters_; }

    template <class Placement, class Accumulation>
    float optical_depth(const Placement& placement, const typename Placement::texel_state& state, const storage<Placement, Accumulation>& in,
                        float depth) const noexcept {
        const float tau = interpolation::optical_depth<Placement, Accumulation>(placement, state, in, depth);
        return parameters_.minus_one ? std::max(tau - hair_, 0.0f) : tau;
    }

    /// The GLSL twin (shaders/reconstruction/hair_count.glsl, after interpolation's): its switch and
    /// one hair's optical depth, as the CPU rounded it.
    static std::string glsl_defines() { return "#define HS_OWN_OPTICAL_DEPTH\n"; }
    template <class Set>
    void glsl_uniforms(Set&& set) const {
        set("hs_hair_optical_depth", parameters_.minus_one ? hair_ : 0.0f);
    }

private:
    hair_count_parameters parameters_;
    float hair_ = hair_count_parameters{}.hair_optical_depth();
};

} // namespace hairshadow
