#pragma once
/// @file
/// Density clustering's per-texel bins (Mertens et al. 2004, sections 3.2-3.3). Fragment depths are
/// clustered by k-means with weights b = -ln(1 - alpha), summed in fixed point so that no order of the
/// fragments changes a bit: K centres start uniform between the texel's nearest and furthest fragment
/// and take one iteration (the weighted means); a second pass gives each cluster's weighted standard
/// deviation around its mean. Cluster j's histogram bin spans
/// mu_j +- sqrt(3) sigma_j (a uniform distribution's width from its variance); overlapping bins meet at
/// the midpoint of the overlap; a fragment outside every bin goes to the nearest cluster.

#include <hairshadow/placement/layer_position.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
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

    void prepare(const fragment_buffer&) const noexcept {}
    void prepare(const depth_extent&) const noexcept {}

    template <class Fragment>
    void prepare_texel(std::span<const Fragment> fragments, texel_state& s) const noexcept {
        s.sigma.fill(-1.0f);
        if (fragments.empty()) return;
        float lo = fragments[0].depth, hi = lo;
        for (const auto& f : fragments) lo = std::min(lo, f.depth), hi = std::max(hi, f.depth);
        // Initial centres: the middles of K equal parts of [nearest, furthest].
        std::array<float, K> centre;
        for (int j = 0; j < K; ++j) centre[std::size_t(j)] = lo + (hi - lo) * (float(j) + 0.5f) / float(K);
        // One k-means iteration: weighted means of the fragments nearest each centre. The sums are
        // exact integers (fixed_sum), so no order of the fragments changes them, and the GPU's compute
        // build, summing in whatever order its threads run, gets the same means bit for bit.
        std::array<std::int64_t, K> weight{}, sum{};
        for (const auto& f : fragments) {
            const auto j = std::size_t(nearest(centre, f.depth, [](int) { return true; }));
            const double b = fragment_optical_depth(f);
            weight[j] += fixed_sum(b);
            sum[j] += fixed_sum(b * double(f.depth)); // exact in double: two floats' product
        }
        for (std::size_t j = 0; j < std::size_t(K); ++j) {
            s.mean[j] = weight[j] > 0 ? float(double(sum[j]) / double(weight[j])) : centre[j];
            s.sigma[j] = weight[j] > 0 ? 0.0f : -1.0f;
        }
        // Second pass: weighted variance of each cluster's fragments around its mean.
        std::array<std::int64_t, K> var_weight{}, var_sum{};
        for (const auto& f : fragments) {
            const auto j = std::size_t(nearest(s.mean, f.depth, [&](int i) { return s.sigma[std::size_t(i)] >= 0.0f; }));
            const double b = fragment_optical_depth(f), d = double(f.depth) - s.mean[j];
            var_weight[j] += fixed_sum(b);
            var_sum[j] += fixed_sum(b * d * d);
        }
        for (std::size_t j = 0; j < std::size_t(K); ++j)
            if (s.sigma[j] >= 0.0f && var_weight[j] > 0) s.sigma[j] = float(std::sqrt(double(var_sum[j]) / double(var_weight[j])));
    }

    /// A k-means term in fixed point, 2^-36 (truncated toward zero): sums of up to 2^24 terms of
    /// optical depth below 7 (alpha <= HAIRSHADOW_ALPHA_MAX) times a depth within [-2, 2] stay exact.
    static std::int64_t fixed_sum(double x) noexcept { return std::int64_t(x * 68719476736.0); }

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
            return nearest(state_->mean, depth, [&](int i) { return state_->sigma[std::size_t(i)] >= 0.0f; });
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
