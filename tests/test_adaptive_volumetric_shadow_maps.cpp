// Adaptive volumetric shadow maps (avsm): nodes behind sheets of strands at known depths, worked by
// hand; as many nodes as steps keep the exact function; the maps are the same for any order of a
// texel's fragments; more nodes come closer to the exact map on Sintel; the deterministic exp; specs;
// and the builds every method shares.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace hairshadow;

namespace {

/// Sheets of strands at the given world z (the light travels along -z), one strand per texel row.
test::sheets_scene sheets_at(const std::vector<float>& zs, int res) {
    auto scene = test::make_sheets(int(zs.size()), res);
    // The light fitted as make_sheets fits it, over these sheets' depths.
    aabb box;
    box.add({-1, -0.5f, *std::min_element(zs.begin(), zs.end())});
    box.add({1, 0.5f, *std::max_element(zs.begin(), zs.end())});
    scene.light = light_space::fit(light_spec::directional({0, 0, -1}), box, res);
    scene.model = hair_model();
    scene.model.default_thickness = scene.light.texel_size(0.5f);
    scene.sheet_z = zs;
    for (const float z : zs)
        for (const float y : scene.row_y) scene.model.add_strand(std::vector<glm::vec3>{{-1, y, z}, {1, y, z}});
    return scene;
}

} // namespace

TEST_CASE("avsm with four nodes behind three sheets removes the nodes of least area, as worked by hand", "[methods][avsm]") {
    // Sheets of alpha 0.3 at depths d1, d2 = d1 + h, d3 = d2 + 4h (world z 0.5, 0.3, -0.5). The steps
    // make six nodes: (d1, 1) (d1, .7) (d2, .7) (d2, .49) (d3, .49) (d3, .343). Twice the areas of the
    // four inner ones: .3h, .21h, .84h, .588h: (d2, .7) goes. Then .3h, .84h, .588h: (d1, .7) goes,
    // leaving (d1, 1) (d2, .49) (d3, .49) (d3, .343): T falls linearly from 1 to .49 between the
    // first two sheets, and is exact behind the second.
    const auto scene = sheets_at({0.5f, 0.3f, -0.5f}, 64);
    adaptive_volumetric_shadow_maps<4> avsm;
    avsm.build(scene.model, scene.light, test::alpha(0.3f));
    const double b = -std::log(0.7);
    CHECK(avsm.stored_optical_depth(32, 32, 0) == 0.0f);
    CHECK(avsm.stored_optical_depth(32, 32, 1) == Approx(2 * b).epsilon(1e-6));
    CHECK(avsm.stored_optical_depth(32, 32, 2) == Approx(2 * b).epsilon(1e-6));
    CHECK(avsm.stored_optical_depth(32, 32, 3) == Approx(3 * b).epsilon(1e-6));
    const float y = scene.row_y[scene.row_y.size() / 2];
    CHECK(avsm.transmittance(glm::vec3(0.2f, y, 0.9f)) == 1.0f);
    CHECK(avsm.transmittance(glm::vec3(0.2f, y, 0.5f)) == 1.0f);
    CHECK(avsm.transmittance(glm::vec3(0.2f, y, 0.4f)) == Approx(0.745).epsilon(1e-4));
    CHECK(avsm.transmittance(glm::vec3(0.2f, y, 0.45f)) == Approx(0.8725).epsilon(1e-4)); // a quarter of the way to the second
    CHECK(avsm.transmittance(glm::vec3(0.2f, y, 0.0f)) == Approx(0.49).epsilon(1e-5));
    CHECK(avsm.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(0.343).epsilon(1e-5));
}

TEST_CASE("avsm with a node for every step keeps the exact function", "[methods][avsm]") {
    // Five sheets make ten nodes; sixteen keep them all: 0.7^k behind k sheets, at and between them.
    const auto scene = test::make_sheets(5, 64);
    adaptive_volumetric_shadow_maps<16> avsm;
    avsm.build(scene.model, scene.light, test::alpha(0.3f));
    const float y = scene.row_y[scene.row_y.size() / 2];
    for (int k = 0; k <= 5; ++k) {
        const float z = 0.6f - 0.2f * float(k); // between sheet k - 1 and sheet k
        CAPTURE(k);
        CHECK(avsm.transmittance(glm::vec3(0.2f, y, z)) == Approx(std::pow(0.7, k)).epsilon(1e-5));
        if (k < 5) CHECK(avsm.transmittance(glm::vec3(0.2f, y, scene.sheet_z[std::size_t(k)])) == Approx(std::pow(0.7, k)).epsilon(1e-5));
    }
    // The unused nodes repeat the last.
    CHECK(avsm.stored_optical_depth(32, 32, 15) == avsm.stored_optical_depth(32, 32, 9));
    CHECK(avsm.texel(32, 32).data.nodes[15] == avsm.texel(32, 32).data.nodes[9]);
}

TEST_CASE("avsm maps are the same for any order of a texel's fragments", "[methods][avsm][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 128);
    const auto fb = rasterize(m, light);
    // The same fragments, each texel's shuffled.
    std::vector<std::uint64_t> offsets(fb.texel_count() + 1, 0);
    std::vector<fragment> shuffled;
    std::mt19937 rng(7);
    for (std::size_t t = 0; t < fb.texel_count(); ++t) {
        const auto in = fb.texel(t);
        const auto first = shuffled.size();
        shuffled.insert(shuffled.end(), in.begin(), in.end());
        std::shuffle(shuffled.begin() + std::ptrdiff_t(first), shuffled.end(), rng);
        offsets[t + 1] = shuffled.size();
    }
    const fragment_buffer other(fb.resolution(), std::move(offsets), std::move(shuffled));
    adaptive_volumetric_shadow_maps<8> a, b;
    a.build(fb, light);
    b.build(other, light, a.map_extent());
    std::size_t compressed = 0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            REQUIRE(a.texel(x, y) == b.texel(x, y));
            compressed += fb.texel(x, y).size() > 4;
        }
    CHECK(compressed > 1000);
}

TEST_CASE("avsm comes closer to the exact map with more nodes, and keeps each texel's total", "[methods][avsm]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 128);
    const auto fb = rasterize(m, light);
    const deep_shadow_map exact(fb, light);
    adaptive_volumetric_shadow_maps<4> four;
    adaptive_volumetric_shadow_maps<8> eight;
    adaptive_volumetric_shadow_maps<16> sixteen;
    four.build(m, light), eight.build(m, light), sixteen.build(m, light);
    double e4 = 0, e8 = 0, e16 = 0;
    std::size_t queries = 0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            const auto d = exact.depths(x, y);
            if (d.empty()) continue;
            // Behind the furthest fragment every node count gives the texel's whole optical depth.
            const float behind = std::nextafter(d.back(), 2.0f), total = exact.optical_depth(x, y, behind);
            REQUIRE(four.optical_depth(x, y, behind) == Approx(total).epsilon(1e-5));
            REQUIRE(sixteen.optical_depth(x, y, behind) == Approx(total).epsilon(1e-5));
            for (const float z : d) {
                const float q = std::nextafter(z, 2.0f), t = std::exp(-exact.optical_depth(x, y, q));
                e4 += std::abs(four.transmittance(x, y, q) - t);
                e8 += std::abs(eight.transmittance(x, y, q) - t);
                e16 += std::abs(sixteen.transmittance(x, y, q) - t);
                ++queries;
            }
        }
    e4 /= double(queries), e8 /= double(queries), e16 /= double(queries);
    CAPTURE(queries, e4, e8, e16);
    CHECK(queries > 100000);
    CHECK(e16 < e8);
    CHECK(e8 < e4);
    CHECK(e16 < 0.01);
}

TEST_CASE("avsm's exp repeats std::exp within 3e-7 relative", "[methods][avsm]") {
    float worst = 0;
    for (float omega = 0.0f; omega < 80.0f; omega += 0.0037f) {
        const double exact = std::exp(-double(omega));
        worst = std::max(worst, float(std::abs(detail::transmittance_of(omega) - exact) / exact));
    }
    CHECK(worst < 3e-7f);
    CHECK(detail::transmittance_of(0.0f) == 1.0f);
    CHECK(detail::transmittance_of(-1.0f) == 1.0f);
    CHECK(detail::transmittance_of(std::nanf("")) == 1.0f);
    CHECK(detail::transmittance_of(100.0f) == 0.0f);
    CHECK(detail::transmittance_of(std::numeric_limits<float>::infinity()) == 0.0f);
}

TEST_CASE("avsm specs parse N, and refuse bad ones", "[methods][avsm][spec]") {
    CHECK(make_shadow_map("avsm")->method_if<adaptive_volumetric_shadow_maps<8>>() != nullptr);
    CHECK(make_shadow_map("avsm:4")->method_if<adaptive_volumetric_shadow_maps<4>>() != nullptr);
    CHECK(make_shadow_map("avsm:16")->method_if<adaptive_volumetric_shadow_maps<16>>() != nullptr);
    for (const char* bad : {"avsm:", "avsm:2", "avsm:5", "avsm:08", "avsm:8:1", "avsm:8bit", "avsm:8:8bit", "avsm:x", "avsm:-8"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
}

TEST_CASE("avsm maps build tile by tile as from fragments, for any thread count, and through the registry", "[methods][avsm][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    CHECK(test::same_maps_tiled_and_buffered(adaptive_volumetric_shadow_maps<8>(), m, fb, light));

    const auto map = make_shadow_map("avsm:16");
    map->build(m, light);
    adaptive_volumetric_shadow_maps<16> direct;
    direct.build(m, light);
    CHECK(test::same_transmittance(*map, direct, m));
}

TEST_CASE("avsm against Lokovic and Veach's compression of the exact map at the same node count", "[methods][avsm][reference]") {
    // Per texel, the exact step function compressed by Lokovic and Veach's greedy algorithm with the
    // least tolerance (to 1/4096 of its range, by bisection) that leaves at most N vertices, against
    // AVSM's N nodes: the largest |T - T_exact| just behind each fragment, averaged over texels.
    // Their algorithm bounds the error everywhere; AVSM's removes the least area, so its worst is
    // larger, and its mean (what shadows show) is measured beside it.
    // (`hairshadow_tests "avsm against*" -s` prints the numbers docs/methods.md quotes.)
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 128);
    const auto fb = rasterize(m, light);
    const deep_shadow_map exact(fb, light);
    adaptive_volumetric_shadow_maps<8> avsm;
    avsm.build(m, light);
    constexpr std::size_t nodes = 8;
    double worst_avsm = 0, worst_lv = 0, mean_avsm = 0, mean_lv = 0;
    std::size_t texels = 0, queries = 0;
    std::vector<transmittance_vertex> steps, compressed;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            const auto d = exact.depths(x, y);
            const auto omega = exact.optical_depths(x, y);
            if (d.size() < nodes) continue; // fewer fragments than nodes: both nearly exact
            detail::exact_steps(d, omega, steps);
            float lo = 0.0f, hi = 1.0f;
            for (int step = 0; step < 12; ++step) {
                const float eps = 0.5f * (lo + hi);
                compressed.clear();
                detail::compress_function(steps, eps, compressed);
                (compressed.size() <= nodes ? hi : lo) = eps;
            }
            compressed.clear();
            detail::compress_function(steps, hi, compressed);
            REQUIRE(compressed.size() <= nodes);
            double texel_avsm = 0, texel_lv = 0;
            for (std::size_t i = 0; i < d.size(); ++i) {
                const float z = std::nextafter(d[i], 2.0f), t = std::exp(-omega[i]);
                const double ea = std::abs(avsm.transmittance(x, y, z) - t), el = std::abs(detail::transmittance_at(compressed, z) - t);
                texel_avsm = std::max(texel_avsm, ea), texel_lv = std::max(texel_lv, el);
                mean_avsm += ea, mean_lv += el;
                ++queries;
            }
            worst_avsm += texel_avsm, worst_lv += texel_lv;
            ++texels;
        }
    worst_avsm /= double(texels), worst_lv /= double(texels), mean_avsm /= double(queries), mean_lv /= double(queries);
    INFO("texels " << texels << ", worst per texel: AVSM " << worst_avsm << ", Lokovic-Veach " << worst_lv << "; mean: AVSM " << mean_avsm
                   << ", Lokovic-Veach " << mean_lv);
    CHECK(texels > 1000);
    CHECK(worst_lv < worst_avsm);
    CHECK(mean_avsm < mean_lv);
}

TEST_CASE("avsm stores a depth of -0 as 0, so that the maps do not depend on which zero came first", "[methods][avsm]") {
    const light_space light = light_space::fit(light_spec::directional({0, 0, -1}), aabb{{-1, -1, -1}, {1, 1, 1}}, 1);
    for (const float first : {-0.0f, 0.0f}) {
        const fragment_buffer fragments(1, {0, 3}, {{first, 0.3f}, {-first, 0.3f}, {0.5f, 0.2f}});
        adaptive_volumetric_shadow_maps<4> avsm;
        avsm.build(fragments, light);
        const auto& nodes = avsm.texel(0, 0).data.nodes;
        CHECK(std::bit_cast<std::uint32_t>(nodes[0].depth) == 0u);
        CHECK(std::bit_cast<std::uint32_t>(nodes[1].depth) == 0u);
        CHECK(nodes[3].depth == 0.5f);
    }
}
