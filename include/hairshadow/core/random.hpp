#pragma once
/// @file
/// A small seeded generator with a fixed, platform-independent sequence (std distributions are not).

#include <cstdint>

namespace hairshadow {

/// SplitMix64: deterministic for a seed on every platform and compiler.
class random_stream {
public:
    explicit random_stream(std::uint64_t seed) noexcept : state_(seed) {}
    std::uint64_t next() noexcept {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1), 24 bits of precision.
    float uniform() noexcept { return float(next() >> 40) * (1.0f / 16777216.0f); }
    /// Uniform in [lo, hi).
    float uniform(float lo, float hi) noexcept { return lo + (hi - lo) * uniform(); }

private:
    std::uint64_t state_;
};

} // namespace hairshadow
