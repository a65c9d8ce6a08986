#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace hairshadow;

namespace {
hair_model two_point_model(glm::vec3 a, glm::vec3 b, float thickness) {
    hair_model m;
    m.add_strand(std::vector<glm::vec3>{a, b});
    // Two anchor strands fix the bounds, so the map spans [-1, 1] in x and y.
    m.add_strand(std::vector<glm::vec3>{{-1, -1, -1}, {-1, -1, -0.99f}});
    m.add_strand(std::vector<glm::vec3>{{1, 1, 1}, {1, 1, 0.99f}});
    m.default_thickness = thickness;
    return m;
}
} // namespace

TEST_CASE("fragments carry the depth and coverage of their segment", "[raster]") {
    const auto m = two_point_model({-0.5f, 0.1f, 0.25f}, {0.5f, 0.1f, 0.25f}, 0.004f);
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 128);
    const auto fb = rasterize(m, ls);
    const float expected_depth = ls.project({0, 0.1f, 0.25f}).depth;
    const float expected_alpha = 0.004f / ls.texel_size(0.5f);
    const int row = int(ls.project({0, 0.1f, 0.25f}).window.y);
    // Columns whose whole diamond lies between the ends (the end texels depend on the exit rule).
    const int x0 = int(ls.project({-0.5f, 0.1f, 0.25f}).window.x) + 1, x1 = int(ls.project({0.5f, 0.1f, 0.25f}).window.x) - 1;
    int found = 0;
    for (int x = x0; x <= x1; ++x) {
        const auto frags = fb.texel(x, row);
        REQUIRE(frags.size() == 1);
        CHECK(frags[0].depth == Approx(expected_depth).margin(1e-6));
        CHECK(frags[0].alpha == Approx(expected_alpha).epsilon(1e-5));
        ++found;
    }
    CHECK(found > 50);
}

TEST_CASE("depth is interpolated along the segment and alpha can be fixed", "[raster]") {
    const auto m = two_point_model({-0.6f, 0.0f, 0.8f}, {0.6f, 0.05f, -0.8f}, 0.004f);
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 64);
    raster_options o;
    o.fixed_alpha = 0.3f;
    const auto fb = rasterize(m, ls, o);
    const auto a = ls.project({-0.6f, 0.0f, 0.8f}), b = ls.project({0.6f, 0.05f, -0.8f});
    for (int x = int(a.window.x) + 1; x < int(b.window.x); ++x) {
        const float t = (float(x) + 0.5f - a.window.x) / (b.window.x - a.window.x);
        bool hit = false;
        for (int y = 0; y < 64; ++y)
            for (const auto& f : fb.texel(x, y))
                if (f.depth > a.depth && f.depth < b.depth) {
                    CHECK(f.depth == Approx(a.depth + t * (b.depth - a.depth)).margin(1e-3));
                    CHECK(f.alpha == 0.3f);
                    hit = true;
                }
        CHECK(hit);
    }
}

TEST_CASE("zero-length segments produce no fragments", "[raster]") {
    auto m = two_point_model({0.2f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.2f}, 0.01f);
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 64);
    const auto fb = rasterize(m, ls);
    const auto td = ls.locate({0.2f, 0.2f, 0.2f});
    REQUIRE(td);
    CHECK(fb.texel(td->x, td->y).empty());
}

TEST_CASE("1 thread, all threads and any tile size give identical fragments on Sintel", "[raster][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto ls = light_space::fit(light_spec::directional({0.3f, -1, -0.5f}), m.bounds(), 512);
    raster_options one;
    one.exec.threads = 1;
    const auto reference = rasterize(m, ls, one);
    CHECK(reference.size() > 500000);
    raster_options all;
    CHECK(rasterize(m, ls, all) == reference);
    raster_options three;
    three.exec.threads = 3;
    three.tile_size = 16;
    CHECK(rasterize(m, ls, three) == reference);
    all.tile_size = 64;
    CHECK(rasterize(m, ls, all) == reference);
    // Wide lines too.
    one.wide_line_width = 3.0f;
    all.wide_line_width = 3.0f;
    CHECK(rasterize(m, ls, one) == rasterize(m, ls, all));
}

TEST_CASE("pre-filtered wide lines spread a strand's coverage across the band", "[raster][wide]") {
    const auto m = two_point_model({-0.5f, 0.013f, 0.0f}, {0.5f, 0.013f, 0.0f}, 0.004f);
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 128);
    raster_options o;
    o.wide_line_width = 4.0f;
    const auto fb = rasterize(m, ls, o);
    const float thin_alpha = 0.004f / ls.texel_size(0.5f);
    const int x = 64;
    float column_sum = 0;
    int count = 0;
    for (int y = 0; y < 128; ++y)
        for (const auto& f : fb.texel(x, y)) {
            column_sum += f.alpha;
            ++count;
        }
    CHECK(count == 4); // centres within 2 texels of the axis
    CHECK(column_sum == Approx(thin_alpha).epsilon(0.05));
}

TEST_CASE("perspective lights weight coverage by reciprocal depth", "[raster]") {
    // Two equal strands, one near the light and one far from it.
    hair_model m;
    m.add_strand(std::vector<glm::vec3>{{-0.5f, 0.3f, 0.9f}, {0.5f, 0.3f, 0.9f}});
    m.add_strand(std::vector<glm::vec3>{{-0.5f, -0.3f, -0.9f}, {0.5f, -0.3f, -0.9f}});
    m.default_thickness = 0.002f;
    const auto ls = light_space::fit(light_spec::point({0, 0, 4}), m.bounds(), 256);
    const auto fb = rasterize(m, ls);
    auto alpha_at = [&](glm::vec3 p) {
        const auto td = ls.locate(p);
        REQUIRE(td);
        REQUIRE(fb.texel(td->x, td->y).size() == 1);
        return fb.texel(td->x, td->y)[0].alpha;
    };
    const float near_alpha = alpha_at({0.01f, 0.3f, 0.9f}), far_alpha = alpha_at({0.01f, -0.3f, -0.9f});
    CHECK(near_alpha / far_alpha == Approx((4 + 0.9f) / (4 - 0.9f)).epsilon(0.02));
    raster_options flat;
    flat.depth_weighting = false;
    const auto fb_flat = rasterize(m, ls, flat);
    const auto td = ls.locate({0.01f, 0.3f, 0.9f});
    CHECK(fb_flat.texel(td->x, td->y)[0].alpha < near_alpha);
}

TEST_CASE("bad raster options raise argument_error", "[raster][errors]") {
    const auto m = test::grid_model(3, 3);
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 32);
    raster_options o;
    o.fixed_alpha = 1.5f;
    CHECK_THROWS_AS(rasterize(m, ls, o), argument_error);
    o = {};
    o.wide_line_width = -1.0f;
    CHECK_THROWS_AS(rasterize(m, ls, o), argument_error);
}

TEST_CASE("wide lines narrower than 2 texels are refused", "[raster][errors]") {
    const auto m = test::grid_model(3, 3);
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 32);
    for (float width : {1e-30f, 0.5f, 1.9f, 65.0f}) {
        raster_options o;
        o.wide_line_width = width;
        CHECK_THROWS_AS(rasterize(m, ls, o), argument_error);
    }
}

TEST_CASE("a long diagonal segment at high resolution gets one fragment per column", "[raster]") {
    hair_model m;
    m.add_strand(std::vector<glm::vec3>{{-1, -1, 0}, {1, 0.9f, 0}});
    m.add_strand(std::vector<glm::vec3>{{-1, 1, 0.1f}, {-1, 1, 0.2f}});
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), m.bounds(), 4096);
    const auto fb = rasterize(m, ls);
    std::vector<int> per_column(4096, 0);
    for (int y = 0; y < 4096; ++y)
        for (int x = 0; x < 4096; ++x) per_column[std::size_t(x)] += int(fb.texel(x, y).size());
    int columns = 0;
    for (int n : per_column) {
        CHECK(n <= 1);
        columns += n;
    }
    CHECK(columns > 4000);
}

TEST_CASE("a segment from far outside a perspective map is clipped, not dropped", "[raster]") {
    // From near the light, far off-axis (beyond the +-2^20-texel guard band), to the map's centre.
    hair_model m;
    m.add_strand(std::vector<glm::vec3>{{50.0f, 0.0f, -0.002f}, {0.0f, 0.0f, -1.0f}});
    m.default_thickness = 0.001f;
    const auto ls = light_space::fit(light_spec::spot({0, 0, 0}, {0, 0, -1}, 10.0f), m.bounds(), 256);
    REQUIRE(ls.project({50.0f, 0.0f, -0.002f}).window.x > float(1 << 20));
    raster_options o;
    o.fixed_alpha = 0.5f;
    const auto fb = rasterize(m, ls, o);
    int found = 0; // the segment runs along a row boundary, so count the rows on both sides
    for (int y = 126; y < 130; ++y)
        for (int x = 130; x < 250; ++x) found += int(fb.texel(x, y).size());
    CHECK(found > 100);
    CHECK(found < 130);
}

TEST_CASE("a fragment's window parameter, taken in float, is within a few ULP of the exact quotient", "[raster]") {
    // segment_shader::parameter: (p . d) / |d|^2 from float conversions, products rounded on their
    // own and a reciprocal of |d|^2, the same on the CPU, in AVX-512 lanes and on the GPU. Against the
    // exact quotient of the integers, for lengths from one sub-pixel to the guard band's and centres
    // on and beside the segment: each product, the sum and the reciprocal round once, so the error is
    // a few ULP of the larger product over |d|^2 (cancellation near the start) and of t itself.
    const auto ls = light_space::fit(light_spec::directional({0, 0, -1}), {{-1, -1, -1}, {1, 1, 1}}, 256);
    std::mt19937 random(2043);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double band = double(std::int64_t(1) << 20) * double(subpixel_scale);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        const double length = std::exp2(unit(random) * std::log2(band));
        const double angle = unit(random) * 6.283185307179586;
        const double ax = (unit(random) * 2.0 - 1.0) * band, ay = (unit(random) * 2.0 - 1.0) * band;
        detail::prepared_segment s{};
        s.ax = std::int32_t(ax), s.ay = std::int32_t(ay);
        s.bx = std::int32_t(std::clamp(ax + length * std::cos(angle), -band, band));
        s.by = std::int32_t(std::clamp(ay + length * std::sin(angle), -band, band));
        if (s.empty()) continue;
        s.depth_a = 0.25f, s.depth_b = 0.75f, s.inv_w_a = s.inv_w_b = 1.0f;
        const detail::segment_shader shader(ls, raster_options{}, s, {0.001f, 0.001f, 1.0f, 1.0f});
        // A texel near the point at a random parameter (a little before the start or past the end too).
        const double f = unit(random) * 1.2 - 0.1;
        const int x = int(std::floor((s.ax + f * (double(s.bx) - s.ax)) / subpixel_scale)) + int(random() % 3) - 1;
        const int y = int(std::floor((s.ay + f * (double(s.by) - s.ay)) / subpixel_scale)) + int(random() % 3) - 1;
        __extension__ typedef __int128 i128;
        const i128 dx = i128(s.bx) - s.ax, dy = i128(s.by) - s.ay;
        const i128 px = i128(x) * subpixel_scale + subpixel_scale / 2 - s.ax, py = i128(y) * subpixel_scale + subpixel_scale / 2 - s.ay;
        const long double exact = std::clamp((long double)(px * dx + py * dy) / (long double)(dx * dx + dy * dy), 0.0L, 1.0L);
        const long double products = ((long double)(px < 0 ? -px : px) * (long double)(dx < 0 ? -dx : dx) +
                                      (long double)(py < 0 ? -py : py) * (long double)(dy < 0 ? -dy : dy)) /
                                     (long double)(dx * dx + dy * dy);
        const float t = shader.parameter(x, y);
        CAPTURE(s.ax, s.ay, s.bx, s.by, x, y, t, double(exact));
        REQUIRE(std::abs((long double)t - exact) <= std::ldexp(6.0L, -24) * (products + exact));
        REQUIRE(std::signbit(t) == false); // -0 clamps to +0
        ++checked;
    }
    CHECK(checked > 19000);
}

TEST_CASE("segments from beyond the guard band are clipped to it, never dropped", "[raster]") {
    // A spot light's window coordinates run to 2^36 texels near its plane. The clip to the +-2^20-texel
    // band takes its parameter in float, a few ULP off, so an end can land just past the band: it is
    // clamped to it, or the whole segment, inside part and all, would be dropped.
    const auto ls = light_space::fit(light_spec::spot({0, 0, 0}, {0, 0, -1}, 10.0f), {{-1, -1, -1.2f}, {1, 1, -0.001f}}, 256);
    std::mt19937 random(4300);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int beyond = 0;
    for (int i = 0; i < 4000; ++i) {
        const float angle = unit(random) * 6.2831853f, reach = std::exp2(5.0f + unit(random) * 12.0f);
        const glm::vec3 p0{reach * std::cos(angle), reach * std::sin(angle), -0.002f - 0.001f * unit(random)};
        const glm::vec3 p1{0.05f * (unit(random) - 0.5f), 0.05f * (unit(random) - 0.5f), -1.0f};
        const auto pp0 = detail::project_point(ls, p0), pp1 = detail::project_point(ls, p1);
        beyond += std::abs(pp0.projected.window.x) > detail::guard_band || std::abs(pp0.projected.window.y) > detail::guard_band;
        detail::segment_attributes at{0.001f, 0.002f, 1.0f, 0.5f};
        detail::prepared_segment s{};
        CAPTURE(i, p0.x, p0.y, p0.z, p1.x, p1.y);
        REQUIRE(detail::prepare_segment(ls, p0, p1, pp0, pp1, at, s));
        const std::int64_t band = std::int64_t(detail::guard_band) * subpixel_scale;
        REQUIRE(std::max({std::abs(std::int64_t(s.ax)), std::abs(std::int64_t(s.ay)), std::abs(std::int64_t(s.bx)), std::abs(std::int64_t(s.by))}) <= band);
    }
    CHECK(beyond > 3500);
}
