#pragma once
// What the tests of the tiled build share: the models, map equality, the AVX-512 halves' skip and
// the tiled build checked against the fragment-buffer build.
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace test {

using namespace hairshadow;

/// Sintel at 512x512, or a curly model of 3000 strands (a scaled-down copy of the 1.5M-segment
/// benchmark model, dense enough for 60 fragments per texel).
inline const hair_model& test_model(const std::string& name) {
    static const hair_model sintel = read_tfx(test::sintel_hair());
    static const hair_model curly = make_procedural({.style = hair_style::curly, .strands = 3000, .segments = 100, .seed = 1});
    return name == "sintel" ? sintel : curly;
}

/// Every texel of a and b equal, and the same whole-map extent.
template <class Method>
bool same_maps(const Method& a, const Method& b) {
    const int res = a.light().resolution();
    if (res != b.light().resolution()) return false;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x)
            if (!(a.texel(x, y) == b.texel(x, y))) {
                UNSCOPED_INFO("first difference at texel (" << x << ", " << y << ")");
                return false;
            }
    return true;
}

/// Whether the AVX-512 half of a test runs on this CPU; where it cannot (no AVX-512F, a build without
/// the vector paths, or HAIRSHADOW_NO_AVX512 set), says so: a visible skip, not a pass. The scalar
/// half of every such test runs everywhere (the suite runs them again with HAIRSHADOW_NO_AVX512 set).
inline bool avx512_half_runs() {
    if (detail::cpu_has_avx512()) return true;
    WARN("no AVX-512 here: the AVX-512 half of this test is skipped, its scalar half runs");
    return false;
}

struct build_config {
    unsigned threads;
    int tile;
    instruction_set instructions;
};

/// What a test changes in raster_options (std::optional members draw GCC's false maybe-uninitialized
/// warnings when copied at -O3).
struct raster_changes {
    float fixed_alpha = -1.0f; ///< none when negative
    float wide = 0.0f;
    bool depth_weighting = true;
};

/// The tiled build against the fragment-buffer build with the tiled build's own whole-map extent,
/// for several thread counts, tile sizes and both line walks.
template <class Method>
void check_tiled_equals_buffer(const hair_model& model, const light_space& light, raster_changes changes = {}) {
    raster_options base;
    if (changes.fixed_alpha >= 0.0f) base.fixed_alpha = changes.fixed_alpha;
    base.wide_line_width = changes.wide;
    base.depth_weighting = changes.depth_weighting;
    const std::vector<build_config> configs = {{1, 64, instruction_set::scalar}, {2, 64, instruction_set::automatic},
                                               {3, 16, instruction_set::automatic}, {8, 37, instruction_set::scalar},
                                               {2, 200, instruction_set::automatic}, {1, 8, instruction_set::automatic}};
    base.exec.threads = 1;
    const fragment_buffer fragments = rasterize(model, light, base);
    Method reference;
    for (const auto& c : configs) {
        CAPTURE(c.threads, c.tile, int(c.instructions));
        raster_options o = base;
        o.exec.threads = c.threads;
        o.tile_size = c.tile;
        o.instructions = c.instructions;
        Method tiled;
        tiled.build(model, light, o);
        reference.build(fragments, light, tiled.map_extent(), execution{1});
        CHECK(tiled.fragment_count() == fragments.size());
        CHECK(same_maps(tiled, reference));
    }
}

} // namespace test
