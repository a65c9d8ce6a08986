#pragma once
/// @file
/// Configuration macros of hairshadow. Each one may be defined before the first include to override it.

/// Library version.
#define HAIRSHADOW_VERSION_MAJOR 0
#define HAIRSHADOW_VERSION_MINOR 1
#define HAIRSHADOW_VERSION_PATCH 0

/// Largest accepted shadow-map resolution (texels per side).
#ifndef HAIRSHADOW_MAX_RESOLUTION
#define HAIRSHADOW_MAX_RESOLUTION 16384
#endif

/// Sub-pixel precision of the line rasteriser, in bits. Window coordinates are snapped to 1/2^bits of a
/// texel before the line rule is applied, as GL implementations do (GL_SUBPIXEL_BITS is 8 on llvmpipe
/// and on NVIDIA), so that the CPU and GL back ends see the same fragments. 1 to 9: the line rule's
/// 32-bit words hold guard-band coordinates at up to 9 bits (raster/line_rule.hpp).
#ifndef HAIRSHADOW_SUBPIXEL_BITS
#define HAIRSHADOW_SUBPIXEL_BITS 8
#endif

/// Largest fragment alpha: alpha is clamped below 1 so that -ln(1 - alpha) stays finite.
#ifndef HAIRSHADOW_ALPHA_MAX
#define HAIRSHADOW_ALPHA_MAX 0.999f
#endif

/// Largest file the readers accept, in bytes (a guard against absurd sizes before anything is read).
#ifndef HAIRSHADOW_MAX_FILE_BYTES
#define HAIRSHADOW_MAX_FILE_BYTES (std::uint64_t(8) << 30)
#endif

/// Forces inlining on the rasteriser's per-fragment path, where the compiler may otherwise leave a
/// call per fragment, which costs more than the fragment's own work.
#ifndef HAIRSHADOW_ALWAYS_INLINE
#if defined(__GNUC__) || defined(__clang__)
#define HAIRSHADOW_ALWAYS_INLINE __attribute__((always_inline))
#else
#define HAIRSHADOW_ALWAYS_INLINE
#endif
#endif

/// The kernels compiled once, opt in. By default hairshadow is header-only: every function is inline
/// and each file that includes a header compiles what it calls. A program may instead define
/// HAIRSHADOW_SEPARATE_KERNELS in all its files, and HAIRSHADOW_KERNELS_IMPLEMENTATION as well in
/// exactly one, which includes <hairshadow/hairshadow.hpp> (CMake's hairshadow::kernels is that
/// file, tools/kernels.cpp): the non-template kernels (the tiled build's binning and walk, the
/// light's fit, the model's checks, the file readers), three quarters of a method's machine code,
/// are then compiled in that file alone, and the others compile only the templates of the methods
/// they use (docs/performance.md, "What a user pays to compile"). The maps are the same either way.
/// HAIRSHADOW_DECL marks those kernels' entry points; HAIRSHADOW_KERNEL_BODIES says whether this file
/// compiles their bodies.
#if !defined(HAIRSHADOW_SEPARATE_KERNELS)
#define HAIRSHADOW_DECL inline
#define HAIRSHADOW_KERNEL_BODIES 1
#elif defined(HAIRSHADOW_KERNELS_IMPLEMENTATION)
#define HAIRSHADOW_DECL
#define HAIRSHADOW_KERNEL_BODIES 1
#else
#define HAIRSHADOW_DECL
#define HAIRSHADOW_KERNEL_BODIES 0
#endif

namespace hairshadow::detail {
/// x itself, as a rounded float: a fence that keeps the compiler from fusing the multiplication that
/// made x with a later addition. A fused multiply-add rounds once, not twice, so fusing would make
/// the vector and scalar paths of the tiled build, builds with and without -mfma, or the CPU and the
/// GPU's compute build, differ.
HAIRSHADOW_ALWAYS_INLINE inline float rounded(float x) noexcept {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    __asm__("" : "+x"(x));
#endif
    return x;
}
} // namespace hairshadow::detail
