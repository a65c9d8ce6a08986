#pragma once
/// @file
/// Density clustering's per-texel bins (Mertens et al. 2004, sections 3.2-3.3). Fragment depths are
/// clustered by k-means with weights b = -ln(1 - alpha), summed in fixed point so that no order of the
/// fragments changes a bit: K centres start uniform between the texel's nearest and furthest fragment
/// and take one iteration (the weighted means); a second pass gives each cluster's weighted standard
/// deviation around its mean. Cluster j's histogram bin spans
/// mu_j +- sqrt(3) sigma_j (a uniform distribution's width from its variance); overlapping bins meet at
/// the midpoint of the overlap; a fragment outside every bin goes to the nearest cluster.

#include <hairshadow/placement/detail/clustered_avx512.hpp>
#include <hairshadow/placement/layer_position.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string_view>

namespace hairshadow {

/// K depth clusters per texel, each a histogram bin.
/// @tparam K number of clusters (4 in the paper: one RGBA texture per quantity)
template <int K>
class clustered {
    static_assert(K >= 1, "clustered needs at least one cluster");

public:
    static constexpr int layer_count = K;
    static constexpr bool cumulative = false; ///< a histogram: a fragment adds to its own bin only
    static constexpr bool contiguous = false; ///< bins may leave gaps
    /// Each texel's state depends on its fragments as a set: the depth range is a minimum and a
    /// maximum, and the k-means sums are integers (fixed_sum), which no order changes (order_free_maps).
    static constexpr bool fragment_order_free = true;
    static constexpr std::string_view name = "clustered";
    static constexpr std::string_view glsl_name = "placement/clustered";
    /// gamma = sqrt(3): the half-width of a uniform distribution with standard deviation sigma.
    static constexpr float bin_half_width = std::numbers::sqrt3_v<float>;

    /// The means and standard deviations maps; an empty cluster has sigma < 0.
    struct texel_state {
        std::array<float, K> mean{};
        std::array<float, K> sigma{};
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };
    /// A cluster's bin [lo, hi], after overlaps are split.
    struct bin {
        float lo, hi;
        bool empty;
    };

    void prepare(const depth_extent&) const noexcept {}

    template <class Fragment>
    void prepare_texel(std::span<const Fragment> fragments, texel_state& s) const noexcept {
        prepare_scalar(fragments, [](const Fragment& f) { return fragment_optical_depth(f); }, s);
    }

#if HAIRSHADOW_AVX512_WALK
    /// Fragments in a texel from which the vector paths below beat the scalar ones: below it, the
    /// vectors' set-up and reductions cost more than they save (BENCHMARKS.md, issue 11).
    static constexpr std::size_t vector_worthwhile = 4;
    /// prepare_texel for a texel's optical fragments, sixteen at a time: the same state, bit for bit
    /// (placement/detail/clustered_avx512.hpp).
    HAIRSHADOW_AVX512_TARGET void prepare_texel_avx512(std::span<const optical_fragment> fragments, texel_state& s) const noexcept
        requires(K <= 16) {
        if (fragments.size() < vector_worthwhile) return prepare_texel(fragments, s);
        s.sigma.fill(-1.0f);
        const detail::avx512::texel_scan scan = detail::avx512::texel_scan_of(fragments);
        const std::array<float, K> centre = initial_centres(scan.range.nearest, scan.range.furthest);
        const float b = fragments[0].optical_depth;
        const bool done = scan.one_optical_depth ? vector_k_means<true>(fragments, b, centre, s) : vector_k_means<false>(fragments, b, centre, s);
        if (!done) prepare_texel(fragments, s); // a term beyond the vector's exact range: only absurd depths
    }

    /// prepare_texel_avx512 for a texel whose fragments all have optical depth b, given by their depths
    /// alone (tile_fragments::group_depths): the state its optical fragments give, bit for bit.
    HAIRSHADOW_AVX512_TARGET void prepare_texel_depths_avx512(std::span<const float> depths, float b, texel_state& s) const noexcept
        requires(K <= 16) {
        const auto optical_depth = [b](float) { return b; };
        if (depths.size() < vector_worthwhile) return prepare_scalar(depths, optical_depth, s);
        s.sigma.fill(-1.0f);
        const depth_extent range = detail::avx512::texel_scan_of(depths).range;
        if (!vector_k_means<true>(depths, b, initial_centres(range.nearest, range.furthest), s)) prepare_scalar(depths, optical_depth, s);
    }

    /// layers[i] = assign(s, fragments[i].depth), sixteen at a time, bit for bit.
    HAIRSHADOW_AVX512_TARGET void assign_texel_avx512(const texel_state& s, std::span<const optical_fragment> fragments,
                                                       std::int32_t* layers) const noexcept
        requires(K <= 16) {
        if (fragments.size() < vector_worthwhile) {
            const texel_assigner assign(*this, s);
            for (std::size_t i = 0; i < fragments.size(); ++i) layers[i] = assign(fragments[i].depth);
            return;
        }
        const vector_bins v(*this, s);
        detail::avx512::assign_to_bins<K>(fragments, v.lo.data(), v.hi.data(), v.filled, s.mean.data(), usable_mask(s), layers);
    }

    /// counts[j] += the fragments assign(s, depth) puts in bin j, sixteen at a time: assign_texel_avx512's
    /// layers, counted.
    /// The fragments may be optical fragments or depths alone (tile_fragments::group_depths).
    template <detail::avx512::texel_fragment Fragment>
    HAIRSHADOW_AVX512_TARGET void count_texel_avx512(const texel_state& s, std::span<const Fragment> fragments,
                                                      std::array<std::uint32_t, std::size_t(K)>& counts) const noexcept
        requires(K <= 16) {
        const vector_bins v(*this, s);
        detail::avx512::count_in_bins<K>(fragments, v.lo.data(), v.hi.data(), v.filled, s.mean.data(), usable_mask(s), counts.data());
    }
#endif

    /// A k-means term in fixed point, 2^-36 (truncated toward zero), for x a product of two floats
    /// (exact in double): sums of up to 2^24 terms of optical depth below 7 (alpha <=
    /// HAIRSHADOW_ALPHA_MAX) times a depth within [-2, 2] stay exact. A term of 2^27 or more in size
    /// saturates at 2^63 - 1 units, and NaN gives 0, as the GPU's hs_fixed_product does.
    static std::int64_t fixed_sum(double x) noexcept {
        const double units = x * detail::cluster_fixed_scale;
        if (std::abs(units) < 0x1p63) [[likely]]
            return std::int64_t(units);
        return saturated(units);
    }

    /// The bins of a texel in depth order; adjacent overlapping bins meet at the overlap's midpoint.
    std::array<bin, K> bins(const texel_state& s) const noexcept {
        std::array<bin, K> out;
        int previous = -1;
        for (int j = 0; j < K; ++j) {
            const auto u = std::size_t(j);
            const float sigma = s.sigma[u];
            out[u] = {s.mean[u] - bin_half_width * std::max(sigma, 0.0f), s.mean[u] + bin_half_width * std::max(sigma, 0.0f), sigma < 0.0f};
            if (out[u].empty) continue;
            if (previous >= 0) {
                auto& a = out[std::size_t(previous)];
                if (a.hi > out[u].lo) {
                    // R1 = L2 = (R1 + L2) / 2, kept within both bins so that neither turns inside out.
                    const float mid = std::clamp(0.5f * (a.hi + out[u].lo), a.lo, std::max(a.lo, out[u].hi));
                    a.hi = out[u].lo = mid;
                    out[u].hi = std::max(out[u].hi, mid);
                }
            }
            previous = j;
        }
        return out;
    }

    /// assign() for the fragments of one texel, with the texel's bins worked out once.
    class texel_assigner {
    public:
        texel_assigner(const clustered& placement, const texel_state& s) noexcept : state_(&s), bins_(placement.bins(s)) {}
        /// The bin holding `depth`, or else the cluster with the nearest mean.
        int operator()(float depth) const noexcept {
            for (int j = 0; j < K; ++j) {
                const auto& x = bins_[std::size_t(j)];
                if (!x.empty && depth >= x.lo && (depth < x.hi || (x.lo == x.hi && depth == x.lo))) return j;
            }
            return nearest(state_->mean, depth, [&](int i) { return usable(*state_, i); });
        }

    private:
        const texel_state* state_;
        std::array<bin, K> bins_;
    };
    texel_assigner assigner(const texel_state& s) const noexcept { return {*this, s}; }

    /// The bin holding `depth`, or else the cluster with the nearest mean.
    int assign(const texel_state& s, float depth) const noexcept { return assigner(s)(depth); }
    /// Inside bin j: {j, fraction}; between bins: the end of the bin before; before all: -1.
    layer_position locate(const texel_state& s, float depth) const noexcept {
        const auto b = bins(s);
        layer_position p{-1, 0.0f};
        for (int j = 0; j < K; ++j) {
            const auto& x = b[std::size_t(j)];
            if (x.empty) continue;
            if (!(depth > x.lo)) break;
            if (depth >= x.hi) {
                p = {j, 1.0f};
                continue;
            }
            return {j, (depth - x.lo) / (x.hi - x.lo)};
        }
        return p;
    }
    static constexpr std::size_t global_bytes() noexcept { return 0; }

private:
    /// fixed_sum beyond the int64 range: the largest in size, or 0 for NaN (out of the hot loops).
    [[gnu::cold, gnu::noinline]] static std::int64_t saturated(double units) noexcept {
        const std::int64_t most = std::numeric_limits<std::int64_t>::max();
        return units > 0.0 ? most : units < 0.0 ? -most : 0;
    }
    /// A k-means pass's sums per cluster, in fixed point (fixed_sum).
    struct cluster_sums {
        std::array<std::int64_t, K> weight, sum;
    };
    /// prepare_texel, with each fragment's b from optical_depth(fragment): a texel's fragments may
    /// come as their depths alone, all of one b.
    template <class Fragment, class OpticalDepth>
    void prepare_scalar(std::span<const Fragment> fragments, OpticalDepth&& optical_depth, texel_state& s) const noexcept {
        s.sigma.fill(-1.0f);
        if (fragments.empty()) return;
        const depth_extent range = detail::texel_extent_of(fragments);
        const std::array<float, K> centre = initial_centres(range.nearest, range.furthest);
        // One k-means iteration: weighted means of the fragments nearest each centre. The sums are
        // exact integers (fixed_sum), so no order of the fragments changes them, and the GPU's compute
        // build, summing in whatever order its threads run, gets the same means bit for bit.
        cluster_sums sums{};
        for (const auto& f : fragments) {
            const float depth = detail::depth_of(f);
            const auto j = std::size_t(nearest(centre, depth, [](int) { return true; }));
            const double b = optical_depth(f);
            sums.weight[j] += fixed_sum(b);
            sums.sum[j] += fixed_sum(b * double(depth)); // exact in double: two floats' product
        }
        set_means(sums, centre, s);
        // Second pass: weighted variance of each cluster's fragments around its mean.
        cluster_sums spread{};
        for (const auto& f : fragments) {
            const float depth = detail::depth_of(f);
            const auto j = std::size_t(nearest(s.mean, depth, [&](int i) { return usable(s, i); }));
            const double b = optical_depth(f);
            spread.weight[j] += fixed_sum(b);
            spread.sum[j] += fixed_sum(b * double(squared_distance(depth, s.mean[j])));
        }
        set_sigmas(spread, s);
    }
    /// Initial centres: the middles of K equal parts of [lo, hi].
    static std::array<float, K> initial_centres(float lo, float hi) noexcept {
        std::array<float, K> centre;
        for (int j = 0; j < K; ++j) centre[std::size_t(j)] = lo + (hi - lo) * (float(j) + 0.5f) / float(K);
        return centre;
    }
    /// A fragment's term of the variance sums, before its weight: (depth - mean)^2, each operation
    /// rounded to float (no fused multiply-add), as the GPU's compute pass takes it.
    static float squared_distance(float depth, float mean) noexcept {
        const float d = depth - mean;
        return detail::rounded(d * d);
    }
    /// The k-means step's result: each cluster's weighted mean, or its centre where it took nothing;
    /// sigma 0 marks a cluster that took weight, -1 one that did not. The quotient of the two sums is
    /// taken in float, each sum rounded to float first (their units cancel): operations IEEE 754
    /// rounds correctly, which the GPU does the same from 32-bit words (hs_float_of_signed_words,
    /// hs_div_rn) where a double quotient would need double precision there.
    static void set_means(const cluster_sums& sums, const std::array<float, K>& centre, texel_state& s) noexcept {
        for (std::size_t j = 0; j < std::size_t(K); ++j) {
            s.mean[j] = sums.weight[j] > 0 ? float(sums.sum[j]) / float(sums.weight[j]) : centre[j];
            s.sigma[j] = sums.weight[j] > 0 ? 0.0f : -1.0f;
        }
    }
    /// Each used cluster's weighted standard deviation from its variance sums: the float quotient, as
    /// set_means takes it, and its correctly rounded float square root (hs_sqrt_rn on the GPU).
    static void set_sigmas(const cluster_sums& spread, texel_state& s) noexcept {
        for (std::size_t j = 0; j < std::size_t(K); ++j)
            if (s.sigma[j] >= 0.0f && spread.weight[j] > 0) s.sigma[j] = std::sqrt(float(spread.sum[j]) / float(spread.weight[j]));
    }
    static bool usable(const texel_state& s, int j) noexcept { return s.sigma[std::size_t(j)] >= 0.0f; }
    /// The clusters that took weight, as bits (the vector paths' `usable`).
    static std::uint32_t usable_mask(const texel_state& s) noexcept {
        std::uint32_t m = 0;
        for (int j = 0; j < K && j < 32; ++j) m |= std::uint32_t(usable(s, j)) << j;
        return m;
    }
    static constexpr std::uint32_t all_usable() noexcept { return K >= 32 ? ~0u : (1u << (K % 32)) - 1u; }

#if HAIRSHADOW_AVX512_WALK
    /// A texel's bins as the vector paths take them: bounds apart, and the bins that are not empty as bits.
    struct vector_bins {
        std::array<float, K> lo, hi;
        std::uint32_t filled = 0;
        vector_bins(const clustered& placement, const texel_state& s) noexcept {
            const std::array<bin, K> b = placement.bins(s);
            for (std::size_t j = 0; j < std::size_t(K); ++j) {
                lo[j] = b[j].lo, hi[j] = b[j].hi;
                if (!b[j].empty) filled |= 1u << j;
            }
        }
    };
    /// prepare_texel_avx512's two k-means passes from the initial centres; false where a term is beyond
    /// the vector's exact range, and then `s` is unfinished.
    /// `b` is the first fragment's optical depth (the only one read with OneOpticalDepth): for depths
    /// alone, the b every fragment has.
    template <bool OneOpticalDepth, class Fragment>
    HAIRSHADOW_AVX512_TARGET static bool vector_k_means(std::span<const Fragment> fragments, float b, const std::array<float, K>& centre,
                                                        texel_state& s) noexcept requires(K <= 16) {
        cluster_sums sums{}, spread{};
        if (!detail::avx512::add_cluster_sums<K, false, OneOpticalDepth>(fragments, b, centre.data(), all_usable(), sums.weight.data(), sums.sum.data()))
            return false;
        set_means(sums, centre, s);
        if (!detail::avx512::add_cluster_sums<K, true, OneOpticalDepth>(fragments, b, s.mean.data(), usable_mask(s), spread.weight.data(),
                                                                       spread.sum.data()))
            return false;
        set_sigmas(spread, s);
        return true;
    }
#endif

    template <class Usable>
    static int nearest(const std::array<float, K>& centres, float depth, Usable usable) noexcept {
        int best = -1;
        float best_distance = 0.0f;
        for (int j = 0; j < K; ++j) {
            if (!usable(j)) continue;
            const float d = std::abs(depth - centres[std::size_t(j)]);
            if (best < 0 || d < best_distance) best = j, best_distance = d;
        }
        return best < 0 ? 0 : best;
    }
};

} // namespace hairshadow
