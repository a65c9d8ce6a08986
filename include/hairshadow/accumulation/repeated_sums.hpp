#pragma once
/// @file
/// The sum of n fragments of one optical depth b, as an accumulation adds them one by one: a pure
/// function of n, kept in a table. A texel whose fragments all share b (a model of one alpha, the
/// common case) then sums each layer from its count, with no chain of dependent adds: the same
/// value, bit for bit, as adding them in any order, since every add is the same.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hairshadow::detail {

/// table(n) = Accumulation::add applied n times to b from a zero sum. Grown as counts need it;
/// reset when b changes.
template <class Accumulation>
class repeated_sums {
public:
    using sum_type = typename Accumulation::sum_type;

    /// Uses b (bit for bit) from now on.
    void use(float b) {
        if (!sums_.empty() && std::bit_cast<std::uint32_t>(b) == b_bits_) return;
        b_ = b, b_bits_ = std::bit_cast<std::uint32_t>(b);
        sums_.assign(1, sum_type{});
    }
    /// n fragments of b, added one by one.
    sum_type operator()(std::size_t n) {
        if (n >= sums_.size()) grow(n);
        return sums_[n];
    }
    std::size_t memory_bytes() const noexcept { return sums_.capacity() * sizeof(sum_type); }

private:
    void grow(std::size_t n) {
        sums_.reserve(std::max(n + 1, 2 * sums_.size()));
        while (sums_.size() <= n) sums_.push_back(Accumulation::add(sums_.back(), b_));
    }
    std::vector<sum_type> sums_;
    float b_ = 0.0f;
    std::uint32_t b_bits_ = 0;
};

/// This thread's repeated_sums for Accumulation, set to b. A cache of a pure function, one per thread
/// so that builds on any number of threads share nothing and give the same sums; it holds as many
/// sums as the most fragments one layer of a texel has taken.
template <class Accumulation>
repeated_sums<Accumulation>& repeated_sums_of(float b) {
    thread_local repeated_sums<Accumulation> sums;
    sums.use(b);
    return sums;
}

} // namespace hairshadow::detail
