#pragma once
/// @file
/// Deep opacity maps' per-pixel layers (Yuksel & Keyser 2008, section 3): a depth pass gives each
/// texel the depth z0 of its first fragment; layer k spans [z0 + d_{k-1}, z0 + d_k) with d_0 = 0, the
/// same d_k for every texel. A fragment adds to its layer and every later one.

#include <hairshadow/core/error.hpp>
#include <hairshadow/placement/detail/slices_avx512.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <span>
#include <string>
#include <string_view>

namespace hairshadow {

/// How layer sizes grow with depth.
enum class layer_sizes {
    linear,  ///< layer k is k times as deep as the first (the paper's choice, section 5)
    uniform, ///< all layers equally deep
};

/// What happens to fragments beyond the last layer, z0 + d_K (Yuksel & Keyser, section 3).
enum class beyond_last_layer {
    ignore, ///< they cast no shadow
    clamp,  ///< they join the last layer (the paper's choice: "usually gave reasonable results")
    extend, ///< each texel's layers are stretched to reach its last fragment
};

/// K layers starting at each texel's first fragment.
/// @tparam K number of layers
/// @tparam Sizes how layer depths grow
/// @tparam Beyond what happens to fragments beyond the last layer
template <int K, layer_sizes Sizes = layer_sizes::linear, beyond_last_layer Beyond = beyond_last_layer::clamp>
class per_pixel_depth {
    static_assert(K >= 1, "per_pixel_depth needs at least one layer");

public:
    static constexpr int layer_count = K;
    static constexpr bool cumulative = true;
    /// Each texel's state depends on its fragments' depths as a set (nearest and furthest), not their
    /// order (order_free_maps).
    static constexpr bool fragment_order_free = true;
    static constexpr bool contiguous = true;
    static constexpr std::string_view name = "per_pixel_depth";
    static constexpr std::string_view glsl_name = "placement/per_pixel_depth";
    /// The GLSL twin's configuration and uniforms (gl/maps/policy_glsl.hpp).
    static std::string glsl_defines() {
        return std::string(Sizes == layer_sizes::uniform ? "#define HS_UNIFORM_SIZES\n" : "") +
               (Beyond == beyond_last_layer::ignore ? "#define HS_BEYOND_IGNORE\n" : "") + (Beyond == beyond_last_layer::extend ? "#define HS_BEYOND_EXTEND\n" : "") +
               "#define HS_RELATIVE_BOUNDARY_BITS " + glsl_float_bits(relative_boundaries) + "\n";
    }
    template <class Set>
    void glsl_uniforms(Set&& set) const {
        set("hs_requested_extent", requested_extent_.value_or(0.0f)); // 0: half the map's depth range, as prepare() takes it
    }

    /// The depth map (z0), plus the stretch factor when layers extend to the last fragment.
    struct z0_only {
        float z0 = 0.0f;
        friend bool operator==(const z0_only&, const z0_only&) = default;
    };
    struct z0_and_scale {
        float z0 = 0.0f;
        float scale = 1.0f;
        friend bool operator==(const z0_and_scale&, const z0_and_scale&) = default;
    };
    using texel_state = std::conditional_t<Beyond == beyond_last_layer::extend, z0_and_scale, z0_only>;
    static_assert(sizeof(z0_only) == sizeof(float) && sizeof(z0_and_scale) == 2 * sizeof(float) && offsetof(z0_and_scale, scale) == sizeof(float),
                  "assign_each_avx512 gathers z0 and the stretch as floats");

    /// Layers covering `extent` in linear depth in total (d_K); by default half the depth range of the
    /// whole map, a choice of ours: the paper leaves d_k to the user.
    per_pixel_depth() = default;
    explicit per_pixel_depth(float extent) : requested_extent_(extent) {
        if (!(extent > 0.0f && extent <= 1.0f)) throw argument_error("per_pixel_depth: the layer extent must be in (0, 1]");
    }

    /// The same from the map's depth extent (the GL back end reduces it from its depth-range map).
    void prepare(const depth_extent& e) noexcept {
        extent_ = requested_extent_ ? *requested_extent_ : std::max(0.5f * (e.furthest - e.nearest), 1e-6f);
    }
    /// The depth pass: z0 is the nearest fragment (and, to extend, the furthest sets the stretch).
    template <class Fragment>
    void prepare_texel(std::span<const Fragment> fragments, texel_state& s) const noexcept {
        if (fragments.empty()) return;
        const auto range = detail::texel_extent_of(fragments);
        texel_state_from(range.nearest, range.furthest, s);
    }
    /// The texel's state from its nearest and furthest fragment: all the depth pass needs, so that a
    /// build which sees the texel's fragments among other texels' can reduce them as they come.
    void texel_state_from(float nearest, float furthest, texel_state& s) const noexcept {
        s.z0 = nearest;
        if constexpr (Beyond == beyond_last_layer::extend) s.scale = std::max(1.0f, detail::just_above(furthest - nearest) / extent_);
        else (void)furthest;
    }

    /// d_k / d_K for layer boundary k in [0, K].
    static constexpr float relative_boundary(int k) noexcept {
        if constexpr (Sizes == layer_sizes::linear) return float(k * (k + 1)) / float(K * (K + 1));
        else return float(k) / float(K);
    }
    /// relative_boundary(k) for k in [0, K], computed once.
    static constexpr std::array<float, std::size_t(K) + 1> relative_boundaries = [] {
        std::array<float, std::size_t(K) + 1> b{};
        for (int k = 0; k <= K; ++k) b[std::size_t(k)] = relative_boundary(k);
        return b;
    }();
    /// Depth of boundary k in [0, K] of a texel: z0 + d_k.
    float boundary(const texel_state& s, int k) const noexcept { return s.z0 + span_of(s) * relative_boundary(k); }

    int assign(const texel_state& s, float depth) const noexcept {
        if constexpr (K <= 8) {
            // The layer locate() settles on, counted without a branch (the build calls this for every
            // fragment, and which layer comes next is anybody's guess): the boundaries d_1..d_K the
            // depth has reached. They increase, so the count is the one k with d_k <= rel < d_k+1; K
            // means beyond the last layer; NaN and depths in front reach none.
            const float rel = (depth - s.z0) / span_of(s);
            int k = 0;
            for (int i = 1; i <= K; ++i) k += int(rel >= relative_boundaries[std::size_t(i)]);
            if constexpr (Beyond == beyond_last_layer::ignore) return k == K ? -1 : k;
            else return std::min(k, K - 1);
        } else {
            const auto p = locate(s, depth);
            if (p.index < 0) return 0;
            if (p.index >= K) return Beyond == beyond_last_layer::ignore ? -1 : K - 1;
            return p.index;
        }
    }
#if HAIRSHADOW_AVX512_WALK
    /// assign() for fragments of many texels, sixteen at a time (placement/detail/slices_avx512.hpp).
    HAIRSHADOW_AVX512_TARGET void assign_each_avx512(const texel_state* states, std::span<const std::uint32_t> texels,
                                                     std::span<const float> depths, std::int32_t* layers) const noexcept {
        detail::avx512::assign_per_pixel<K, Sizes == layer_sizes::linear, Beyond == beyond_last_layer::extend, Beyond == beyond_last_layer::ignore>(
            states, extent_, relative_boundaries.data(), texels, depths, layers);
    }
#endif
    layer_position locate(const texel_state& s, float depth) const noexcept {
        const float rel = (depth - s.z0) / span_of(s);
        if (!(rel >= 0.0f)) return {-1, 0.0f};
        if (rel >= 1.0f) return {K, 0.0f};
        float estimate; // closed form of the layer, settled against the boundaries below
        if constexpr (Sizes == layer_sizes::linear) estimate = (std::sqrt(1.0f + 4.0f * rel * float(K * (K + 1))) - 1.0f) * 0.5f;
        else estimate = rel * float(K);
        const int k = detail::settle_layer(estimate, K - 1, rel, [](int i) { return relative_boundaries[std::size_t(i)]; });
        return detail::position_in(k, rel, relative_boundaries[std::size_t(k)], relative_boundaries[std::size_t(k + 1)]);
    }
    static constexpr std::size_t global_bytes() noexcept { return sizeof(float); }
    /// d_K in linear depth.
    float extent() const noexcept { return extent_; }
    /// d_K as given to the constructor; none: half the map's depth range.
    std::optional<float> requested_extent() const noexcept { return requested_extent_; }

private:
    float span_of(const texel_state& s) const noexcept {
        if constexpr (Beyond == beyond_last_layer::extend) return extent_ * s.scale;
        else return extent_;
    }
    std::optional<float> requested_extent_;
    float extent_ = 1.0f;
};

} // namespace hairshadow
