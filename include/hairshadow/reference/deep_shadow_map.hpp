#pragma once
/// @file
/// The exact reference (Lokovic & Veach 2000): every texel keeps its fragments sorted by depth, so the
/// optical depth Omega(z) = sum over fragments in front of z of -ln(1 - alpha_i) and the transmittance
/// T = exp(-Omega) are exact at any depth. This is what infinitely many opacity slices, or depth
/// peeling, would give; every method is measured against it.

#include <hairshadow/core/light.hpp>
#include <hairshadow/core/map_queries.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/raster/fragment.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <span>
#include <vector>

namespace hairshadow {

/// Per-texel sorted fragment lists with cumulative optical depth.
class deep_shadow_map : public map_queries<deep_shadow_map> {
public:
    /// Sorts every texel's fragments by depth (ties keep segment order) and accumulates optical depth.
    deep_shadow_map(const fragment_buffer& fragments, const light_space& light, const execution& exec = {})
        : light_(light), offsets_(fragments.offsets()), depths_(fragments.size()), optical_depths_(fragments.size()) {
        if (fragments.resolution() != light.resolution()) throw argument_error("fragment buffer and light differ in resolution");
        parallel_for(fragments.texel_count(), exec, [&](std::size_t t) {
            const auto in = fragments.texel(t);
            if (in.empty()) return;
            // Sort (depth, arrival) pairs: equal depths keep segment order, for any thread count.
            thread_local std::vector<std::pair<float, std::uint32_t>> order;
            order.resize(in.size());
            for (std::size_t i = 0; i < in.size(); ++i) order[i] = {in[i].depth, std::uint32_t(i)};
            std::sort(order.begin(), order.end());
            double omega = 0.0;
            const std::size_t base = offsets_[t];
            for (std::size_t i = 0; i < order.size(); ++i) {
                omega -= std::log1p(-double(in[order[i].second].alpha));
                depths_[base + i] = order[i].first;
                optical_depths_[base + i] = float(omega);
            }
        }, 1024);
    }

    const light_space& light() const noexcept { return light_; }
    int resolution() const noexcept { return light_.resolution(); }

    /// Sorted depths of texel (x, y)'s fragments.
    std::span<const float> depths(int x, int y) const noexcept { return slice(depths_, x, y); }
    /// Optical depth behind each of texel (x, y)'s fragments (inclusive prefix sums).
    std::span<const float> optical_depths(int x, int y) const noexcept { return slice(optical_depths_, x, y); }

    /// Exact optical depth at `depth` in texel (x, y): the fragments strictly in front count.
    float optical_depth(int x, int y, float depth) const noexcept {
        const auto d = depths(x, y);
        const std::size_t in_front = std::size_t(std::lower_bound(d.begin(), d.end(), depth) - d.begin());
        return in_front == 0 ? 0.0f : optical_depths(x, y)[in_front - 1];
    }
    using map_queries<deep_shadow_map>::transmittance;

    std::size_t fragment_count() const noexcept { return depths_.size(); }
    /// Bytes held by the map: offsets, depths and optical depths.
    std::size_t memory_bytes() const noexcept {
        return offsets_.size() * sizeof(std::uint64_t) + depths_.size() * sizeof(float) + optical_depths_.size() * sizeof(float);
    }

private:
    std::span<const float> slice(const std::vector<float>& v, int x, int y) const noexcept {
        const std::size_t t = std::size_t(y) * std::size_t(light_.resolution()) + std::size_t(x);
        return {v.data() + offsets_[t], std::size_t(offsets_[t + 1] - offsets_[t])};
    }

    light_space light_;
    std::vector<std::uint64_t> offsets_;
    std::vector<float> depths_;
    std::vector<float> optical_depths_;
};

} // namespace hairshadow
