#pragma once
/// @file
/// Named padding: the zero bytes that would otherwise pad the end of a stored struct (a texel of
/// 8-bit layers beside a float depth), so that every write of the struct writes every byte. The maps'
/// hash reads a texel's bytes, and a padding byte holds whatever the build left there.

#include <algorithm>
#include <array>
#include <cstddef>
#include <type_traits>

namespace hairshadow::detail {

/// The bytes that round a struct of `Parts`, laid out in order without padding between them, up to
/// its alignment (an empty part takes none, as under [[no_unique_address]]).
template <class... Parts>
constexpr std::size_t tail_padding() {
    const std::size_t used = ((std::is_empty_v<Parts> ? 0 : sizeof(Parts)) + ... + 0);
    const std::size_t align = std::max({alignof(Parts)...});
    return (align - used % align) % align;
}

/// `Bytes` zero bytes, or nothing (an empty member under [[no_unique_address]]). `Owner`, the struct
/// that holds it, keeps two empty tails apart: two empty members of one type may not share an address,
/// so a texel's empty tail beside its storage's would add a byte.
template <std::size_t Bytes, class Owner>
struct tail_bytes {
    std::array<unsigned char, Bytes> zero{};
    friend bool operator==(const tail_bytes&, const tail_bytes&) = default;
};
template <class Owner>
struct tail_bytes<0, Owner> {
    friend bool operator==(const tail_bytes&, const tail_bytes&) = default;
};

} // namespace hairshadow::detail
