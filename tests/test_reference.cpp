#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

using namespace hairshadow;

TEST_CASE("behind k parallel sheets the exact transmittance is (1 - alpha)^k", "[reference]") {
    const auto scene = test::make_sheets(4, 128);
    REQUIRE(scene.model.bounds().center().y == Approx(0.0f).margin(1e-6));
    const float alpha = 0.3f;
    raster_options o;
    o.fixed_alpha = alpha;
    const deep_shadow_map dsm(rasterize(scene.model, scene.light, o), scene.light);
    int checked = 0;
    for (float y : {scene.row_y[5], scene.row_y[scene.row_y.size() / 2], scene.row_y[scene.row_y.size() - 6]})
        for (float x : {-0.7f, 0.0f, 0.33f, 0.8f})
            for (int k = 0; k <= 4; ++k) {
                const float z = k == 0 ? 0.6f : scene.sheet_z[std::size_t(k - 1)] - 0.1f; // just behind sheet k
                CAPTURE(x, y, z, k);
                CHECK(dsm.transmittance({x, y, z}) == Approx(std::pow(1.0f - alpha, float(k))).epsilon(1e-5));
                ++checked;
            }
    CHECK(checked == 60);
}

TEST_CASE("the exact optical depth sums -ln(1 - alpha) over the fragments in front", "[reference]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto ls = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), 128);
    const auto fb = rasterize(m, ls);
    const deep_shadow_map dsm(fb, ls);
    REQUIRE(dsm.fragment_count() == fb.size());
    random_stream rng(7);
    int busy = 0;
    for (int i = 0; i < 2000; ++i) {
        const int x = int(rng.uniform() * 128), y = int(rng.uniform() * 128);
        const float z = rng.uniform();
        double omega = 0;
        for (const auto& f : fb.texel(x, y))
            if (f.depth < z) omega -= std::log(1.0 - double(f.alpha));
        busy += fb.texel(x, y).size() > 10;
        REQUIRE(dsm.optical_depth(x, y, z) == Approx(omega).epsilon(1e-5).margin(1e-6));
        REQUIRE(dsm.transmittance(x, y, z) == Approx(std::exp(-omega)).epsilon(1e-5).margin(1e-7));
    }
    CHECK(busy > 100);
    CHECK(dsm.transmittance(64, 64, 0.0f) == 1.0f); // nothing is in front of depth 0
}

TEST_CASE("Lokovic-Veach compression stays within its tolerance with fewer vertices", "[reference][compression]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto ls = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), 128);
    const deep_shadow_map dsm(rasterize(m, ls), ls);
    for (float tolerance : {0.002f, 0.02f, 0.1f}) {
        const compressed_deep_shadow_map c(dsm, tolerance);
        CAPTURE(tolerance);
        CHECK(c.vertex_count() < 2 * dsm.fragment_count());
        float worst = 0;
        for (int y = 0; y < 128; y += 3)
            for (int x = 0; x < 128; x += 3) {
                const auto depths = dsm.depths(x, y);
                std::vector<float> probes{0.0f, 1.0f};
                for (float d : depths) {
                    probes.push_back(d);
                    probes.push_back(std::nextafter(d, 2.0f));
                    probes.push_back(d + 1e-3f);
                }
                for (float z : probes) worst = std::max(worst, std::abs(c.transmittance(x, y, z) - dsm.transmittance(x, y, z)));
            }
        CHECK(worst <= tolerance * 1.0001f + 1e-6f);
    }
    const compressed_deep_shadow_map coarse(dsm, 0.1f), fine(dsm, 0.002f);
    CHECK(coarse.vertex_count() < fine.vertex_count());
}

TEST_CASE("compression of a hand-made function", "[reference][compression]") {
    // Four equal steps of 0.1 each at depths 0.1, 0.2, 0.3, 0.4: with tolerance 0.06 one straight
    // ramp cannot follow them all, but a few segments can.
    const std::vector<transmittance_vertex> steps{{0.1f, 1.0f}, {0.1f, 0.9f}, {0.2f, 0.9f}, {0.2f, 0.8f},
                                                  {0.3f, 0.8f}, {0.3f, 0.7f}, {0.4f, 0.7f}, {0.4f, 0.6f}};
    std::vector<transmittance_vertex> out;
    detail::compress_function(steps, 0.06f, out);
    CHECK(out.size() < steps.size());
    CHECK(out.front().depth == 0.1f);
    CHECK(out.back().depth == 0.4f);
    CHECK(std::abs(out.back().transmittance - 0.6f) <= 0.06f);
    // With a tolerance above the whole drop, a single ramp would do but a single vertex is not enough.
    out.clear();
    detail::compress_function(steps, 0.5f, out);
    CHECK(out.size() == 2);
}

TEST_CASE("a compression tolerance outside (0, 1) is refused", "[reference][compression][errors]") {
    const auto scene = test::make_sheets(2, 32);
    const deep_shadow_map dsm(rasterize(scene.model, scene.light), scene.light);
    CHECK_THROWS_AS(compressed_deep_shadow_map(dsm, 0.0f), argument_error);
    CHECK_THROWS_AS(compressed_deep_shadow_map(dsm, 1.0f), argument_error);
    CHECK_THROWS_AS(compressed_deep_shadow_map(dsm, std::nanf("")), argument_error);
}

TEST_CASE("the exact steps' transmittance is std::exp's, bit for bit, where it underflows too", "[reference][compression]") {
    std::size_t zeros = 0;
    for (float omega = 80.0f; omega < 112.0f; omega = std::nextafter(omega, 200.0f)) { // every float in [80, 112)
        const float want = std::exp(-omega), got = detail::exact_transmittance(omega);
        if (std::bit_cast<std::uint32_t>(want) != std::bit_cast<std::uint32_t>(got)) FAIL("omega " << omega << ": " << got << " against " << want);
        zeros += got == 0.0f;
    }
    CHECK(zeros > 0);
    for (const float omega : {0.0f, -0.0f, 1e-30f, 0.5f, 20.0f, std::numeric_limits<float>::infinity()})
        CHECK(std::bit_cast<std::uint32_t>(detail::exact_transmittance(omega)) == std::bit_cast<std::uint32_t>(std::exp(-omega)));
    CHECK(std::isnan(detail::exact_transmittance(std::nanf(""))));
}

TEST_CASE("batch queries equal single queries and points outside the map are lit", "[reference]") {
    const auto m = make_procedural({.style = hair_style::curly, .strands = 400, .segments = 24});
    const auto ls = light_space::fit(light_spec::directional({0, -1, 0}), m.bounds(), 128);
    const deep_shadow_map dsm(rasterize(m, ls), ls);
    std::vector<float> batch(m.point_count());
    dsm.transmittance(m.points, batch, {.depth_bias = 1e-3f});
    for (std::size_t i = 0; i < m.point_count(); i += 17) CHECK(batch[i] == dsm.transmittance(m.points[i], {.depth_bias = 1e-3f}));
    CHECK(dsm.transmittance(glm::vec3(100, 0, 0)) == 1.0f);
    CHECK(dsm.memory_bytes() >= dsm.fragment_count() * 8);
}

namespace {
/// Lokovic & Veach's exact map computed here from the whole-map fragment buffer, the way it was
/// built before the streamed build: each texel's fragments stably sorted by depth, optical depth
/// summed in double. The streamed build must give these bits.
void require_equals_buffer_build(const deep_shadow_map& streamed, const fragment_buffer& fragments) {
    REQUIRE(streamed.fragment_count() == fragments.size());
    const int res = fragments.resolution();
    std::vector<fragment> sorted;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto in = fragments.texel(x, y);
            sorted.assign(in.begin(), in.end());
            std::stable_sort(sorted.begin(), sorted.end(), [](const fragment& a, const fragment& b) { return a.depth < b.depth; });
            const auto d = streamed.depths(x, y), o = streamed.optical_depths(x, y);
            REQUIRE(d.size() == sorted.size());
            double omega = 0.0;
            for (std::size_t i = 0; i < sorted.size(); ++i) {
                omega -= std::log1p(-double(sorted[i].alpha));
                if (d[i] != sorted[i].depth || o[i] != float(omega)) FAIL("texel (" << x << ", " << y << ") fragment " << i << " differs");
            }
        }
}

bool same_vertices(const compressed_deep_shadow_map& a, const compressed_deep_shadow_map& b) {
    const int res = a.light().resolution();
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto va = a.vertices(x, y), vb = b.vertices(x, y);
            if (va.size() != vb.size()) return false;
            for (std::size_t i = 0; i < va.size(); ++i)
                if (va[i].depth != vb[i].depth || va[i].transmittance != vb[i].transmittance) return false;
        }
    return true;
}
} // namespace

TEST_CASE("the streamed exact map equals the map of the whole fragment buffer, bit for bit, for any threads and tiles", "[reference][streamed]") {
    const auto sintel = read_tfx(test::sintel_hair());
    const auto curly = make_procedural({.style = hair_style::curly, .strands = 300, .segments = 24});
    struct scene {
        const hair_model* model;
        light_spec light;
        int resolution;
    };
    for (const scene& s : {scene{&sintel, light_spec::directional({0, -1, -1}), 160}, scene{&sintel, light_spec::point({0.4f, 0.6f, 0.9f}), 96},
                           scene{&curly, light_spec::directional({1, -1, 0}), 200}}) {
        const auto ls = light_space::fit(s.light, s.model->bounds(), s.resolution);
        for (const float wide : {0.0f, 2.5f}) {
            raster_options o;
            o.wide_line_width = wide;
            const fragment_buffer fragments = rasterize(*s.model, ls, o);
            for (const unsigned threads : {1u, 2u, 5u})
                for (const int tile : {16, 64, 200}) {
                    CAPTURE(s.resolution, wide, threads, tile);
                    o.exec.threads = threads, o.tile_size = tile;
                    std::size_t reports = 0, last = 0;
                    const deep_shadow_map streamed(*s.model, ls, o, [&](std::size_t done, std::size_t total) { ++reports, last = total; (void)done; });
                    CHECK(reports == last);
                    CHECK(reports == detail::map_tiling(s.resolution, tile).tile_count());
                    require_equals_buffer_build(streamed, fragments);
                    const compressed_deep_shadow_map from_exact(streamed, 0.01f), streamed_compressed(*s.model, ls, 0.01f, o);
                    CHECK(streamed_compressed.fragment_count() == fragments.size());
                    CHECK(same_vertices(streamed_compressed, from_exact));
                }
        }
    }
}

TEST_CASE("many threads write the streamed map's tiles apart (small enough for ThreadSanitizer)", "[reference][streamed][parallel]") {
    const auto curly = make_procedural({.style = hair_style::curly, .strands = 200, .segments = 16});
    const auto ls = light_space::fit(light_spec::directional({1, -1, 0}), curly.bounds(), 64);
    raster_options o;
    o.tile_size = 16;
    const fragment_buffer fragments = rasterize(curly, ls, o);
    o.exec.threads = 4;
    const deep_shadow_map streamed(curly, ls, o);
    require_equals_buffer_build(streamed, fragments);
    const compressed_deep_shadow_map from_exact(streamed, 0.01f), streamed_compressed(curly, ls, 0.01f, o);
    CHECK(same_vertices(streamed_compressed, from_exact));
}

TEST_CASE("streamed builds refuse bad options and tolerances", "[reference][streamed][errors]") {
    const auto scene = test::make_sheets(2, 32);
    raster_options o;
    for (const int tile : {4, 0, -1, 1025, std::numeric_limits<int>::max()}) { // no division by zero, no overflow: the options are checked first
        o.tile_size = tile;
        CHECK_THROWS_AS(deep_shadow_map(scene.model, scene.light, o), argument_error);
        CHECK_THROWS_AS(compressed_deep_shadow_map(scene.model, scene.light, 0.01f, o), argument_error);
    }
    CHECK_THROWS_AS(compressed_deep_shadow_map(scene.model, scene.light, 0.0f), argument_error);
    CHECK_THROWS_AS(compressed_deep_shadow_map(scene.model, scene.light, std::nanf("")), argument_error);
}
