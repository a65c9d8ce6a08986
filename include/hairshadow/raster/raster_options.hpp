#pragma once
/// @file
/// How segments become fragments: the options shared by the rasteriser and the tiled build.

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/parallel.hpp>

#include <optional>

namespace hairshadow {

/// The instructions the tiled build walks its lines with. Every choice gives the same fragments, bit
/// for bit; only the time differs.
enum class instruction_set {
    automatic, ///< the best this CPU runs: AVX-512 where it has AVX-512F (x86-64, GCC or Clang), else scalar
    scalar,    ///< portable C++
    avx512,    ///< AVX-512F; argument_error where the CPU or the compiler has none
};

/// How segments become fragments.
struct raster_options {
    execution exec{};
    /// When set, every fragment gets this alpha instead of its coverage (`--alpha A`).
    std::optional<float> fixed_alpha{};
    /// Pre-filtered wide lines (Mertens et al. 2004, section 3.4): a screen-aligned band of this many
    /// texels across each segment with a Gaussian profile, instead of the aliased line rule. 0 = off;
    /// otherwise at least 2, below which texel-centre samples of the profile alias.
    float wide_line_width = 0.0f;
    /// Perspective lights: weight coverage by reciprocal depth (Mertens et al. 2004, section 3.4), i.e.
    /// divide the thickness by the texel's footprint at the fragment's depth rather than at mid-range.
    bool depth_weighting = true;
    /// Side of the square tiles that are rasterised (and built) in parallel, in texels. 64 keeps a
    /// tile's fragments in cache while making fewer segment-tile pairs than 32 or 16
    /// (docs/performance.md). Larger tiles cut fewer segments in two, which can speed up the streamed
    /// methods (DOM, OSM, occupancy) on large maps, but each thread's store then holds a larger dense
    /// tile's fragments (BENCHMARKS.md, "Tiles of 128 at large maps").
    int tile_size = 64;
    /// The tiled build's line walk (the fragment_buffer rasteriser is scalar).
    instruction_set instructions = instruction_set::automatic;

    /// Throws argument_error for a bad alpha, wide-line width or tile size.
    void check() const {
        if (fixed_alpha && !(*fixed_alpha >= 0.0f && *fixed_alpha <= 1.0f)) throw argument_error("fixed alpha must be in [0, 1]");
        if (!(wide_line_width == 0.0f || (wide_line_width >= 2.0f && wide_line_width <= 64.0f)))
            throw argument_error("wide line width must be 0 (off) or in [2, 64] texels");
        if (tile_size < 8 || tile_size > 1024) throw argument_error("tile size must be in [8, 1024]");
    }
    friend bool operator==(const raster_options&, const raster_options&) = default;
};

} // namespace hairshadow
