#pragma once
/// @file
/// Reconstruction by adaptive nodes: adaptive volumetric shadow maps (Salvi et al. 2010). Each texel
/// keeps a transmittance function of at most N nodes (depth, transmittance), linear between nodes,
/// 1 in front of the first and the last node's behind the last. Occluders are inserted one at a
/// time; whenever the function has more than N nodes, the node whose removal changes the area under
/// it least goes (the paper's section 3.2: the area of the triangle the node makes with its two
/// neighbours).
///
/// Choices the paper leaves open, documented and tested (tests/test_adaptive_volumetric_shadow_maps.cpp):
/// - Order. The paper inserts in arrival order, so its maps depend on it. Here a texel's fragments are
///   inserted in depth order, ties by optical depth: an order of the fragments' values alone, so the
///   maps are the same for any thread count and segment order, and GL's lists give the CPU's maps.
/// - A hair's fragment is a segment of no thickness (the paper's insertion with its entry and exit at
///   one depth): a vertical step of two nodes, (z, T before) and (z, T after), the first left out
///   where the function's last node already is it.
/// - The first node (where the shadow starts) and the last (the texel's whole optical depth) are
///   never removed; among the others the first of the smallest areas goes.
/// - Nodes keep the optical depth Omega in front of them, and T = exp(-Omega) is computed by
///   detail::transmittance_of, whose float operations the GLSL twin repeats, so that the areas and
///   the choice of node are the same bits on GL. A texel's unused nodes repeat its last, and a texel
///   with no fragment is all zero: Omega = 0, no shadow.

#include <hairshadow/config.hpp>
#include <hairshadow/raster/fragment.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hairshadow {

/// One node of an adaptive transmittance function: a depth and the optical depth in front of it.
struct transmittance_node {
    float depth;
    float optical_depth;
    friend bool operator==(const transmittance_node&, const transmittance_node&) = default;
};

/// A texel's nodes, sorted by depth; unused ones repeat the last.
template <int N>
struct adaptive_node_list {
    std::array<transmittance_node, std::size_t(N)> nodes{};
    friend bool operator==(const adaptive_node_list&, const adaptive_node_list&) = default;
};

namespace detail {

/// exp(-omega) for omega >= 0, in float operations that IEEE rounds exactly (no fused multiply-adds),
/// which shaders/reconstruction/adaptive_nodes.glsl repeats operation for operation: omega = k ln 2 +
/// r with |r| <= ln 2 / 2 (ln 2 in two parts, k ln2_hi exact for k < 128), then 2^-k times a degree-7
/// Taylor polynomial of exp(-r) (its first term left out below 3e-9 relative). Within 3e-7 relative
/// of std::exp; 0 at or beyond 87.3 (below the smallest normal float), 1 for NaN or below 0.
inline float transmittance_of(float omega) noexcept {
    if (!(omega > 0.0f)) return 1.0f;
    if (!(omega < 87.3f)) return 0.0f;
    const float k = std::floor(rounded(omega * 1.44269502f) + 0.5f);
    const float r = (omega - rounded(k * 0.693145752f)) - rounded(k * 1.42860677e-6f);
    // 1/5040, 1/720, 1/120, 1/24, 1/6 rounded to float, written out so that no compiler folds them differently.
    float p = -0.000198412701f;
    for (const float c : {0.00138888892f, -0.00833333377f, 0.0416666679f, -0.166666672f, 0.5f, -1.0f, 1.0f}) p = c + rounded(r * p);
    return rounded(p * std::bit_cast<float>(std::uint32_t(127 - int(k)) << 23));
}

/// The area of the triangle a node makes with its neighbours in the (depth, T) plane, twice over:
/// what removing it changes the area under the function by. In the GLSL twin's order of operations.
inline float removal_area(float d0, float t0, float d1, float t1, float d2, float t2) noexcept {
    return std::abs(rounded(rounded(d1 - d0) * rounded(t2 - t0)) - rounded(rounded(d2 - d0) * rounded(t1 - t0)));
}

/// Salvi et al.'s streaming compression, a texel's fragments inserted in depth order (see the file's
/// comment): at most N nodes. Each inner node keeps its removal area, which changes only when a
/// neighbour does (a node pushed behind it, or one removed beside it), so a removal scans N areas
/// rather than computing them: the same areas, so the same nodes, as recomputing each time (the
/// GLSL twin recomputes).
template <int N>
class adaptive_node_builder {
public:
    /// Inserts a fragment of optical depth b > 0 at `depth`, behind every fragment inserted so far.
    void insert(float depth, float b) noexcept {
        // The step's top node has the last node's optical depth, so its transmittance too.
        if (count_ == 0) push(depth, total_, 1.0f);
        else if (nodes_[count_ - 1].depth != depth || nodes_[count_ - 1].omega != total_) push(depth, total_, nodes_[count_ - 1].t);
        total_ = total_ + b;
        push(depth, total_, transmittance_of(total_));
        while (count_ > N) remove(least_area());
    }
    /// The nodes, the last repeated into the unused ones.
    void finish(adaptive_node_list<N>& out) const noexcept {
        if (count_ == 0) return; // nothing inserted: the texel stays all zero
        for (int i = 0; i < N; ++i) {
            const auto& n = nodes_[std::size_t(std::min(i, count_ - 1))];
            out.nodes[std::size_t(i)] = {n.depth, n.omega};
        }
    }
    int count() const noexcept { return count_; }

private:
    struct node {
        float depth, omega, t, area;
    };
    void push(float depth, float omega, float t) noexcept {
        nodes_[std::size_t(count_)] = {depth, omega, t, 0.0f};
        ++count_;
        if (count_ >= 3) update_area(count_ - 2);
    }
    void update_area(int i) noexcept {
        const auto &a = nodes_[std::size_t(i - 1)], &b = nodes_[std::size_t(i)], &c = nodes_[std::size_t(i + 1)];
        nodes_[std::size_t(i)].area = removal_area(a.depth, a.t, b.depth, b.t, c.depth, c.t);
    }
    int least_area() const noexcept {
        int best = 1;
        for (int i = 2; i < count_ - 1; ++i)
            if (nodes_[std::size_t(i)].area < nodes_[std::size_t(best)].area) best = i;
        return best;
    }
    void remove(int i) noexcept {
        for (int j = i; j < count_ - 1; ++j) nodes_[std::size_t(j)] = nodes_[std::size_t(j + 1)];
        --count_;
        if (i - 1 >= 1) update_area(i - 1);
        if (i <= count_ - 2) update_area(i);
    }

    std::array<node, std::size_t(N + 2)> nodes_{};
    float total_ = 0.0f;
    int count_ = 0;
};

} // namespace detail

/// Optical depth from at most N adaptive nodes per texel (adaptive volumetric shadow maps).
template <int N>
class adaptive_nodes {
    static_assert(N >= 4 && N % 2 == 0, "adaptive nodes: an even N of at least 4 (GL keeps two nodes a texture layer; the first and last are never removed)");

public:
    static constexpr int node_count = N;
    static constexpr std::string_view name = "adaptive_nodes";
    static constexpr std::string_view glsl_name = "reconstruction/adaptive_nodes";
    /// Any placement: the nodes need no layers (the method uses one uniform slice and ignores it).
    template <class Placement>
    static constexpr bool accepts = true;

    template <class Placement, class Accumulation>
    using storage = adaptive_node_list<N>;

    /// Sorts the texel's fragments by (depth, optical depth) and inserts them in that order.
    template <class Placement, class Accumulation, class Fragment>
    void build(const Placement&, const typename Placement::texel_state&, std::span<const Fragment> fragments,
               storage<Placement, Accumulation>& out) const {
        thread_local std::vector<std::pair<float, float>> order;
        order.clear();
        for (const auto& f : fragments) {
            // A fragment of no optical depth, or of no finite depth, changes nothing; -0 sorts as 0.
            const float b = fragment_optical_depth(f);
            if (b > 0.0f && std::isfinite(f.depth)) order.emplace_back(f.depth == 0.0f ? 0.0f : f.depth, b);
        }
        if (order.empty()) return;
        std::sort(order.begin(), order.end());
        detail::adaptive_node_builder<N> builder;
        for (const auto& [depth, b] : order) builder.insert(depth, b);
        builder.finish(out);
    }

    /// The optical depth in front of `depth`: 0 up to the first node (the exact map counts the
    /// fragments strictly in front), T linear between nodes, the last node's behind the last.
    template <class Placement, class Accumulation>
    float optical_depth(const Placement&, const typename Placement::texel_state&, const storage<Placement, Accumulation>& in,
                        float depth) const noexcept {
        return optical_depth_of_nodes(in, depth);
    }
    static float optical_depth_of_nodes(const adaptive_node_list<N>& in, float depth) noexcept {
        const auto& n = in.nodes;
        if (!(depth > n[0].depth)) return 0.0f;
        int i = 1;
        while (i < N && !(n[std::size_t(i)].depth >= depth)) ++i;
        if (i == N) return n[N - 1].optical_depth;
        const auto& a = n[std::size_t(i - 1)];
        const auto& b = n[std::size_t(i)];
        if (a.optical_depth == b.optical_depth) return a.optical_depth;
        const float ta = detail::transmittance_of(a.optical_depth), tb = detail::transmittance_of(b.optical_depth);
        const float t = (depth - a.depth) / (b.depth - a.depth);
        const float transmittance = ta + t * (tb - ta);
        return transmittance > 0.0f ? std::min(-std::log(transmittance), b.optical_depth) : b.optical_depth;
    }

    /// The nodes' optical depths, for inspection.
    template <class Placement>
    static constexpr int stored_maps = N;
    template <class Placement, class Accumulation>
    static float stored_optical_depth(const storage<Placement, Accumulation>& in, int k) noexcept {
        return in.nodes[std::size_t(k)].optical_depth;
    }

    /// The GLSL twin (shaders/reconstruction/adaptive_nodes.glsl) takes N.
    static std::string glsl_defines() { return "#define HS_NODES " + std::to_string(N) + "\n"; }
};

} // namespace hairshadow
