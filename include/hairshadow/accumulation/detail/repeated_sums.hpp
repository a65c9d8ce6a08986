#pragma once
/// @file
/// The sum of n fragments of one optical depth b, as an accumulation adds them one by one: a pure
/// function of n, kept in a table. A texel whose fragments all share b (a model of one alpha, the
/// common case) then sums each layer from its count, with no chain of dependent adds per texel once
/// the table holds its counts: the same value, bit for bit, as adding them in order, since every add
/// is the same.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

namespace hairshadow::detail {

/// sums(n) = b added n times to a zero sum by Accumulation::add. The first `tabled` are kept,
/// filled as counts reach them and started afresh when b changes; larger counts go on adding from the
/// last. A fixed array: a build that uses it allocates nothing.
template <class Accumulation>
class repeated_sums {
public:
    using sum_type = typename Accumulation::sum_type;
    static constexpr std::size_t tabled = 1024;

    /// Uses b (bit for bit) from now on.
    void use(float b) noexcept {
        if (std::bit_cast<std::uint32_t>(b) == b_bits_) return;
        b_ = b, b_bits_ = std::bit_cast<std::uint32_t>(b);
        top_ = 0; // sums_[0], the empty sum, holds for any b
    }
    /// n fragments of b, added one by one.
    sum_type operator()(std::size_t n) noexcept {
        if (n <= top_) return sums_[n];
        const std::size_t last = std::min(n, tabled - 1);
        for (; top_ < last; ++top_) sums_[top_ + 1] = Accumulation::add(sums_[top_], b_);
        sum_type sum = sums_[last];
        for (std::size_t i = last; i < n; ++i) sum = Accumulation::add(sum, b_);
        return sum;
    }

private:
    std::array<sum_type, tabled> sums_{}; ///< sums_[0] the empty sum, always
    std::size_t top_ = 0;                 ///< sums_[0, top_] hold the sums for b_
    float b_ = 0.0f;
    std::uint32_t b_bits_ = 0;            ///< b_'s bits: +0 before the first use()
};

/// This thread's repeated_sums for Accumulation, set to b. A cache of a pure function, one per thread
/// so that builds on any number of threads share nothing and give the same sums, and held in the
/// thread's own storage so that no build allocates for it.
template <class Accumulation>
repeated_sums<Accumulation>& repeated_sums_of(float b) noexcept {
    thread_local repeated_sums<Accumulation> sums;
    sums.use(b);
    return sums;
}

} // namespace hairshadow::detail
