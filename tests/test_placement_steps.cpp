// The placements' per-texel steps in the tiled build: the streamed depth pass, assign_each, and
// density clustering's scalar and AVX-512 steps, each against the policy's own assign.
#include "tiled_build_support.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <numeric>
#include <random>
#include <set>
#include <thread>
#include <tuple>

using namespace hairshadow;
using namespace test;

TEST_CASE("the streamed depth pass gives widen_extent's ranges, signed zeros and ties included, on both paths", "[tiled][placement]") {
    // Texels whose nearest or furthest depth is a zero met with both signs (which sign stays depends on
    // the comparisons' order and strictness), whose bounds tie, and random depths over many texels.
    // The ranges' bits must be the reference's.
    std::vector<std::uint32_t> texels;
    std::vector<float> depths;
    const std::vector<std::vector<float>> values = {{0.0f, -0.0f}, {0.0f, -0.0f, 0.5f, 0.5f}, {-0.0f, 0.0f, -0.5f, -2.0f}, {1.0f, 1.0f}};
    std::mt19937 random(11);
    for (std::uint32_t k = 0; k < 8; ++k)
        for (int i = 0; i < 40; ++i) texels.push_back(k), depths.push_back(values[k % 4][random() % values[k % 4].size()]);
    std::uniform_real_distribution<float> anywhere(-3.0f, 3.0f);
    for (int i = 0; i < 5000; ++i) texels.push_back(8 + std::uint32_t(random() % 200)), depths.push_back(anywhere(random));
    std::shuffle(texels.begin() + 320, texels.end(), random);
    constexpr float inf = std::numeric_limits<float>::infinity();
    std::vector<depth_extent> expected(208, depth_extent{inf, -inf});
    for (std::size_t i = 0; i < texels.size(); ++i) detail::widen_extent(expected[texels[i]], depths[i]);
    for (const instruction_set path : {instruction_set::scalar, instruction_set::avx512}) {
        if (path == instruction_set::avx512 && !detail::cpu_has_avx512()) continue;
        std::vector<detail::negated_range> ranges(expected.size(), detail::negated_range{inf, inf});
        detail::add_depths(ranges.data(), texels.data(), depths.data(), texels.size(), path);
        std::size_t differing = 0;
        for (std::size_t k = 0; k < ranges.size(); ++k) {
            const float furthest = -ranges[k].neg_furthest;
            differing += std::memcmp(&ranges[k].nearest, &expected[k].nearest, sizeof(float)) != 0 ||
                         std::memcmp(&furthest, &expected[k].furthest, sizeof(float)) != 0;
            CHECK_FALSE(detail::empty_range(ranges[k]));
        }
        INFO("path " << int(path));
        CHECK(differing == 0);
    }
}

TEMPLATE_TEST_CASE("assign_each gives assign's layers, one at a time and sixteen at a time, at and beside every boundary", "[tiled][placement][avx512]",
                   per_pixel_depth<3>, (per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::ignore>),
                   (per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::extend>), per_pixel_depth<8>, uniform_slices<16>,
                   gamma_slices<16>, uniform_slices<5>, depth_range<128>, depth_range<24>, depth_range<1>, per_pixel_depth<16>,
                   (per_pixel_depth<128, layer_sizes::uniform, beyond_last_layer::extend>),
                   (per_pixel_depth<32, layer_sizes::linear, beyond_last_layer::ignore>)) {
    const bool vector_half = avx512_half_runs();
    using state = typename TestType::texel_state;
    TestType placement;
    placement.prepare(depth_extent{0.1f, 0.9f});
    // Texels with z0 (and, to extend, furthest) spread over the map's range.
    std::vector<state> states(37);
    for (std::size_t k = 0; k < states.size(); ++k)
        placement.texel_state_from(0.1f + 0.02f * float(k), 0.1f + 0.02f * float(k) + 0.013f * float(k % 11), states[k]);
    // Depths at each boundary of each texel, a few units in the last place either side, in front of the
    // first and beyond the last; a count that leaves a partial last step.
    std::vector<std::uint32_t> texels;
    std::vector<float> depths;
    for (std::uint32_t k = 0; k < states.size(); ++k)
        for (int b = 0; b <= TestType::layer_count; ++b) {
            float d = placement.boundary(states[k], b);
            for (int ulp = 0; ulp < 3; ++ulp) d = std::nextafter(d, -1.0f);
            for (int ulp = 0; ulp < 7; ++ulp, d = std::nextafter(d, 2.0f)) texels.push_back(k), depths.push_back(d);
            texels.push_back(k), depths.push_back(-1.0f);
            texels.push_back(k), depths.push_back(3.0f);
        }
    texels.push_back(5), depths.push_back(0.5f);
    REQUIRE(texels.size() % 16 != 0);
    std::vector<std::int32_t> scalar(texels.size(), -7), vector(texels.size(), -7);
    detail::assign_each(placement, std::span<const state>(states), texels, depths, std::span(scalar), instruction_set::scalar);
    if (vector_half) detail::assign_each(placement, std::span<const state>(states), texels, depths, std::span(vector), instruction_set::avx512);
    else vector = scalar;
    std::size_t differing = 0, wrong = 0;
    std::vector<bool> seen(std::size_t(TestType::layer_count) + 1);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        differing += scalar[i] != vector[i];
        wrong += scalar[i] != placement.assign(states[texels[i]], depths[i]);
        seen[std::size_t(scalar[i] + 1)] = true;
    }
    CHECK(differing == 0);
    CHECK(wrong == 0);
    CHECK(std::count(seen.begin(), seen.end(), true) >= TestType::layer_count); // every layer met
}

namespace {
/// Texels of every count up to 70 (partial last steps; below clustered::vector_worthwhile, the
/// scalar steps), then ones made to meet each special case of density clustering's steps.
std::vector<std::vector<optical_fragment>> clustering_texels() {
    random_stream random(7);
    std::vector<std::vector<optical_fragment>> texels;
    for (int n = 1; n <= 70; ++n) {
        std::vector<optical_fragment> t;
        for (int i = 0; i < n; ++i) t.push_back({random.uniform(0.2f, 0.8f), random.uniform(0.0f, 2.0f)});
        texels.push_back(t);
        // Repeated depths (ties between centres), few distinct values, and clusters that take nothing.
        for (auto& f : t) f.depth = 0.25f + 0.125f * float(int(f.depth * 8.0f) % 3);
        texels.push_back(t);
        // One optical depth throughout (a model of one alpha): the vector passes count the fragments
        // each cluster takes instead of adding their weights.
        for (auto& f : t) f = {random.uniform(0.2f, 0.8f), 0.7f};
        texels.push_back(t);
    }
    texels.push_back(std::vector<optical_fragment>(23, {0.5f, 0.3f}));                       // one depth: bins of no width
    texels.push_back({{0.0f, 0.1f}, {-0.0f, 0.2f}, {0.5f, 0.1f}, {-0.0f, 0.4f}});            // a zero of either sign at the front
    texels.push_back({{0.4f, 0.0f}, {0.6f, 0.0f}, {0.7f, 0.0f}, {0.3f, 0.0f}, {0.2f, 0.0f}}); // no weight: no cluster usable
    // Terms past the vector's exact range (2^15), in the second pass and in the first, but within the
    // scalar's (2^27).
    texels.push_back({{0.4f, 0.5f}, {1000.0f, 1.5f}, {0.7f, 0.25f}, {0.41f, 0.5f}, {0.9f, 1.0f}});
    texels.push_back(std::vector<optical_fragment>(5, {20000.0f, 2.0f}));
    texels.push_back({{0.4f, 0.5f}, {1000.0f, 0.5f}, {0.7f, 0.5f}, {0.41f, 0.5f}, {0.9f, 0.5f}}); // one b, past the range in the second pass
    texels.push_back({{0.4f, 0.0f}, {0.6f, -0.0f}, {0.7f, 0.0f}, {0.3f, -0.0f}, {0.2f, 0.0f}});  // b of zero, either sign: one b
    std::vector<optical_fragment> last_differs(40, {0.3f, 1.25f});
    for (std::size_t i = 0; i < last_differs.size(); ++i) last_differs[i].depth += 0.01f * float(i);
    last_differs.back().optical_depth = 1.5f; // one b but in the last, partial step
    texels.push_back(last_differs);
    std::vector<optical_fragment> spread;
    for (int i = 0; i < 200; ++i) spread.push_back({i % 2 ? -1.5f + 0.01f * float(i) : 1.9f - 0.005f * float(i), 6.5f});
    texels.push_back(spread); // the whole range of depths and the largest optical depth
    std::vector<optical_fragment> zeros(20, {0.5f, 1.0f});
    zeros[3].depth = 0.0f, zeros[17].depth = -0.0f; // in order +0 comes first; in lanes, -0 (lane 1)
    texels.push_back(zeros);
    return texels;
}
} // namespace

TEMPLATE_TEST_CASE("density clustering's per-texel steps: the scalar layers and counts are assign's; the vector pre-pass, bin assignment and bin counts give the scalar state, layers and counts, bit for bit",
                   "[tiled][placement][avx512]", clustered<1>, clustered<3>, clustered<4>, clustered<8>, clustered<16>) {
    const bool vector_half = avx512_half_runs();
    using state = typename TestType::texel_state;
    const TestType placement;
    const auto texels = clustering_texels();
    constexpr std::size_t K = std::size_t(TestType::layer_count);
    std::size_t differing_states = 0, differing_layers = 0, differing_counts = 0, differing_ranges = 0, differing_one_b = 0, texels_of_one_b = 0,
                fragments = 0, differing_maps = 0, texels_alone = 0, layered = 0;
    for (const auto& t : texels) {
        const std::span<const optical_fragment> in(t);
        // The scalar half: the texel's range is its nearest and furthest depth, and the grouped build's
        // layers and counts, through their dispatch, are assign's.
        const depth_extent range = detail::texel_extent_of(in);
        const auto [lo, hi] = std::minmax_element(t.begin(), t.end(), [](const auto& a, const auto& b) { return a.depth < b.depth; });
        differing_ranges += !(range.nearest == lo->depth && range.furthest == hi->depth);
        state scalar;
        placement.prepare_texel(in, scalar);
        std::vector<std::int32_t> layers(t.size(), -7);
        for (std::size_t i = 0; i < t.size(); ++i, ++fragments) layers[i] = placement.assign(scalar, t[i].depth);
        std::vector<std::int32_t> visited; // every fragment, with its layer or -1 (texel_assigner's)
        detail::for_each_layer(placement, scalar, in, instruction_set::scalar, [&](int k, const optical_fragment&) { visited.push_back(k); });
        differing_layers += visited != layers;
        std::array<std::uint32_t, K> expected{};
        for (const std::int32_t k : layers)
            if (k >= 0) ++expected[std::size_t(k)], ++layered;
        differing_counts += detail::layer_counts(placement, scalar, in, instruction_set::scalar) != expected;
#if HAIRSHADOW_AVX512_WALK // the vector members exist only where the vector paths are compiled
        if (!vector_half) continue;
        const detail::avx512::texel_scan scan = detail::avx512::texel_scan_of(in);
        differing_ranges += std::memcmp(&range, &scan.range, sizeof(range)) != 0;
        const bool one_b = std::all_of(t.begin(), t.end(), [&](const optical_fragment& f) { return f.optical_depth == t[0].optical_depth; });
        differing_one_b += scan.one_optical_depth != one_b;
        texels_of_one_b += one_b;
        state vector;
        placement.prepare_texel_avx512(in, vector);
        differing_states += std::memcmp(&scalar, &vector, sizeof(state)) != 0;
        std::vector<std::int32_t> vector_layers(t.size(), -7);
        placement.assign_texel_avx512(scalar, in, vector_layers.data());
        differing_layers += vector_layers != layers;
        // The grouped build's per-texel steps through their dispatch, against their scalar forms.
        state dispatched;
        detail::prepare_texel(placement, in, dispatched, instruction_set::avx512);
        differing_states += !(dispatched == scalar);
        std::vector<std::int32_t> visited_vector;
        detail::for_each_layer(placement, scalar, in, instruction_set::avx512, [&](int k, const optical_fragment&) { visited_vector.push_back(k); });
        differing_layers += visited_vector != visited;
        // The layers' counts (interpolation's build for a texel of one b), vector and dispatched.
        std::array<std::uint32_t, K> counted{};
        placement.count_texel_avx512(scalar, in, counted);
        differing_counts += counted != expected;
        differing_counts += detail::layer_counts(placement, scalar, in, instruction_set::avx512) != expected;
        // The texel as its depths alone (tile_fragments::group_depths, where a map has one b), against
        // its fragments all given the first one's b: the same range, state, counts and maps.
        std::vector<optical_fragment> one_of_b = t;
        std::vector<float> depths;
        for (auto& f : one_of_b) {
            f.optical_depth = t[0].optical_depth;
            depths.push_back(f.depth);
        }
        const std::span<const optical_fragment> uniform(one_of_b);
        const std::span<const float> alone(depths);
        const depth_extent alone_range = detail::avx512::texel_scan_of(alone).range;
        differing_ranges += std::memcmp(&range, &alone_range, sizeof(range)) != 0;
        state expected_state, from_depths;
        placement.prepare_texel(uniform, expected_state);
        placement.prepare_texel_depths_avx512(alone, t[0].optical_depth, from_depths);
        differing_states += std::memcmp(&expected_state, &from_depths, sizeof(state)) != 0;
        std::array<std::uint32_t, K> expected_alone{}, counted_alone{};
        for (const float d : depths)
            if (const int k = placement.assign(expected_state, d); k >= 0) ++expected_alone[std::size_t(k)];
        placement.count_texel_avx512(expected_state, alone, counted_alone);
        differing_counts += counted_alone != expected_alone;
        interpolation::storage<TestType, float_accumulation> built, built_alone;
        interpolation::build<TestType, float_accumulation>(placement, expected_state, uniform, built);
        interpolation::build_from_depths<TestType, float_accumulation>(placement, expected_state, alone, t[0].optical_depth, built_alone);
        differing_maps += std::memcmp(&built, &built_alone, sizeof(built)) != 0;
        ++texels_alone;
#endif
    }
    CHECK(fragments > 2000);
    CHECK(layered > 1000);
    CHECK(differing_counts == 0);
    CHECK(differing_ranges == 0);
    CHECK(differing_layers == 0);
    if (vector_half) {
        CHECK(differing_one_b == 0);
        CHECK(texels_of_one_b > 70);
        CHECK(differing_states == 0);
        CHECK(differing_maps == 0);
        CHECK(texels_alone == texels.size());
    }
}
