#pragma once
/// @file
/// Which vector instructions the tiled build runs on this CPU (raster_options::instructions): the
/// AVX-512 paths are compiled with GCC's or Clang's target attribute and chosen at run time, so a
/// build for plain x86-64 still uses them where the CPU has them. The macro HAIRSHADOW_NO_AVX512
/// leaves them out of a build; the environment variable HAIRSHADOW_NO_AVX512 (set, not empty and not
/// "0") makes a process act as on a CPU without AVX-512, as the tests do to run the portable paths.

#include <hairshadow/core/error.hpp>
#include <hairshadow/raster/raster_options.hpp>

#include <cstdlib>
#include <string_view>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(HAIRSHADOW_NO_AVX512)
#define HAIRSHADOW_AVX512_WALK 1
// GCC 12's intrinsics make their "undefined" vectors by self-initialisation, which -Wuninitialized
// reports wherever they inline (GCC bug 105593); the warning is located in the header, so it is
// silenced there.
#if defined(__clang__)
#include <immintrin.h>
#else
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
/// The attribute of every function that uses AVX-512 intrinsics.
#define HAIRSHADOW_AVX512_TARGET __attribute__((target("avx512f")))
#else
#define HAIRSHADOW_AVX512_WALK 0
#endif

namespace hairshadow {

namespace detail {
/// Does this CPU (and this compiler) run the AVX-512 paths, and does the environment let it?
inline bool cpu_has_avx512() noexcept {
#if HAIRSHADOW_AVX512_WALK
    static const bool has = [] {
        const char* off = std::getenv("HAIRSHADOW_NO_AVX512");
        return __builtin_cpu_supports("avx512f") && !(off && *off && std::string_view(off) != "0");
    }();
    return has;
#else
    return false;
#endif
}
} // namespace detail

#if HAIRSHADOW_AVX512_WALK
namespace detail::avx512 {
/// x itself: the multiplication that made x is not fused with a later addition (see detail::rounded).
HAIRSHADOW_AVX512_TARGET inline __m512 rounded(__m512 x) noexcept {
    __asm__("" : "+v"(x));
    return x;
}
} // namespace detail::avx512
#endif

/// The instruction set `requested` resolves to on this CPU: automatic picks the best there is.
/// Throws argument_error for avx512 where the CPU or the compiler has none.
inline instruction_set resolve(instruction_set requested) {
    if (requested == instruction_set::automatic) return detail::cpu_has_avx512() ? instruction_set::avx512 : instruction_set::scalar;
    if (requested == instruction_set::avx512 && !detail::cpu_has_avx512())
        throw argument_error("this CPU (or this build) has no AVX-512F for the tiled build; use instruction_set::scalar or automatic");
    return requested;
}

} // namespace hairshadow
