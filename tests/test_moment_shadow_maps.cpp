// Moment shadow maps (msm:4, 6, 8): the moments behind sheets of strands at known depths, worked by
// hand; M / 2 sheets, which M moments determine, give exactly the sheets' shadow between them for any
// overestimation; the roots of the canonical polynomials, a point far out included; the bounds
// (overestimation 0 below the exact optical depth, 1 above it) behind five sheets and on Sintel
// against the exact map; specs; and the builds every method shares.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

using namespace hairshadow;

namespace {

template <int M = 4>
moment_shadow_maps<M> with_overestimation(float overestimation) {
    return moment_shadow_maps<M>{depth_range<1>(), power_moments<M>({.overestimation = overestimation})};
}

/// The 4-moment reconstruction as it was written before M became a parameter (Hamburger 4MSM in
/// closed form, float, in its own order of operations): the generic code must give its bits.
float closed_form_4msm(const float* stored, float s, float overestimation, float bias) {
    const float b0 = stored[0], keep = 1.0f - bias, pull = bias * 0.375f;
    const float b1 = keep * (stored[1] / b0), b2 = keep * (stored[2] / b0) + pull;
    const float b3 = keep * (stored[3] / b0), b4 = keep * (stored[4] / b0) + pull;
    const float z0 = 2.0f * s - 1.0f;
    const float d11 = b2 - b1 * b1;
    const float l21d11 = b3 - b1 * b2;
    const float l21 = l21d11 / d11;
    const float d22 = (b4 - b2 * b2) - l21d11 * l21;
    float c1 = z0 - b1;
    float c2 = z0 * z0 - b2 - l21 * c1;
    c1 = c1 / d11;
    c2 = c2 / d22;
    c1 = c1 - l21 * c2;
    const float c0 = 1.0f - (c1 * b1 + c2 * b2);
    const float p = c1 / c2, q = c0 / c2;
    const float r = std::sqrt(0.25f * p * p - q);
    const float z1 = -0.5f * p - r, z2 = -0.5f * p + r;
    const float f0 = overestimation, f1 = z1 < z0 ? 1.0f : 0.0f, f2 = z2 < z0 ? 1.0f : 0.0f;
    const float f01 = (f1 - f0) / (z1 - z0), f12 = (f2 - f1) / (z2 - z1), f012 = (f12 - f01) / (z2 - z0);
    const float q2 = f012, q1 = (f01 - f012 * z1) - q2 * z0;
    const float q0 = f0 - (f01 - f012 * z1) * z0;
    const float share = q0 + b1 * q1 + b2 * q2;
    return b0 * (std::isfinite(share) ? share : f0);
}

} // namespace

TEST_CASE("four moments give the closed-form 4MSM's bits", "[methods][msm]") {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    long compared = 0, differ = 0, singular = 0;
    for (const float overestimation : {0.0f, 0.25f, 1.0f}) {
        const power_moments<4> generic({.overestimation = overestimation});
        for (int texel = 0; texel < 20000; ++texel) {
            // 1 to 12 fragments, a third of them on the range's ends or its quarters (a texel of one or
            // two depths leaves the Hankel matrix singular but for the bias).
            double terms[5] = {};
            const int fragments = 1 + int(random() % 12);
            for (int i = 0; i < fragments; ++i)
                power_moments<4>::project(random() % 3 == 0 ? float(random() % 5) / 4.0f : unit(random), 0.05f + unit(random), terms);
            float stored[5];
            for (int k = 0; k < 5; ++k) stored[k] = float(terms[k]);
            singular += fragments <= 2;
            const float s = unit(random);
            const float a = generic.series_optical_depth(stored, s), b = closed_form_4msm(stored, s, overestimation, 5e-7f);
            ++compared;
            differ += std::bit_cast<std::uint32_t>(a) != std::bit_cast<std::uint32_t>(b);
        }
    }
    CAPTURE(compared, singular);
    CHECK(singular > 5000);
    CHECK(differ == 0);
}

TEST_CASE("moment shadow maps store the optical depth and its power moments behind sheets of strands", "[methods][msm]") {
    // Five sheets of alpha 0.3 at z = 0.5 .. -0.3: in each texel's range at z = -1, -0.5, 0, 0.5, 1.
    const auto scene = test::make_sheets(5, 64);
    const double b = -std::log(0.7);
    moment_shadow_maps<> msm;
    msm.build(scene.model, scene.light, test::alpha(0.3f));
    CHECK(msm.stored_optical_depth(32, 32, 0) == Approx(5 * b).epsilon(1e-6));
    CHECK(msm.stored_optical_depth(32, 32, 1) == Approx(0.0).margin(1e-5));
    CHECK(msm.stored_optical_depth(32, 32, 2) == Approx(2.5 * b).epsilon(1e-5));  // 1 + 1/4 + 0 + 1/4 + 1
    CHECK(msm.stored_optical_depth(32, 32, 3) == Approx(0.0).margin(1e-5));
    CHECK(msm.stored_optical_depth(32, 32, 4) == Approx(2.125 * b).epsilon(1e-5)); // 1 + 1/16 + 0 + 1/16 + 1
    const float y = scene.row_y[scene.row_y.size() / 2];
    CHECK(msm.transmittance(glm::vec3(0.2f, y, 0.9f)) == 1.0f);
    CHECK(msm.transmittance(glm::vec3(0.2f, y, 0.5f)) == 1.0f);
    CHECK(msm.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(std::pow(0.7, 5)).epsilon(1e-5));
}

TEST_CASE("six and eight moments store every power behind sheets of strands", "[methods][msm]") {
    // Three sheets of alpha 0.3, in each texel's range at z = -1, 0 and 1: b z^j sums to
    // b ((-1)^j + 0^j + 1), 2 b for even j, 0 for odd.
    const auto scene = test::make_sheets(3, 64);
    const double b = -std::log(0.7);
    moment_shadow_maps<8> msm;
    msm.build(scene.model, scene.light, test::alpha(0.3f));
    CHECK(msm.stored_optical_depth(32, 32, 0) == Approx(3 * b).epsilon(1e-6));
    for (int j = 1; j <= 8; ++j) {
        CAPTURE(j);
        if (j % 2) CHECK(msm.stored_optical_depth(32, 32, j) == Approx(0.0).margin(1e-5));
        else CHECK(msm.stored_optical_depth(32, 32, j) == Approx(2 * b).epsilon(1e-5));
    }
    CHECK(power_moments<6>().bias() == 5e-6f);
    CHECK(power_moments<8>().bias() == 5e-5f);
    CHECK(power_moments<8>({.bias = 1e-6f}).bias() == 1e-6f);
}

TEST_CASE("M / 2 sheets, which M moments determine, give the sheets' shadow between them", "[methods][msm]") {
    const auto check = []<int M>(std::integral_constant<int, M>, double tolerance) {
        const int sheets = M / 2;
        const auto scene = test::make_sheets(sheets, 64);
        const float y = scene.row_y[scene.row_y.size() / 2];
        for (const float overestimation : {0.0f, 0.25f, 1.0f}) {
            auto msm = with_overestimation<M>(overestimation);
            msm.build(scene.model, scene.light, test::alpha(0.3f));
            for (int behind = 1; behind < sheets; ++behind)
                for (const float between : {0.1f, 0.5f, 0.9f}) {
                    const float z = scene.sheet_z[std::size_t(behind - 1)] + between * (scene.sheet_z[std::size_t(behind)] - scene.sheet_z[std::size_t(behind - 1)]);
                    CAPTURE(M, overestimation, behind, z);
                    CHECK(msm.transmittance(glm::vec3(0.2f, y, z)) == Approx(std::pow(0.7, behind)).epsilon(tolerance));
                }
            CHECK(msm.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(std::pow(0.7, sheets)).epsilon(1e-5));
        }
    };
    check(std::integral_constant<int, 4>{}, 1e-3);
    check(std::integral_constant<int, 6>{}, 1e-3);
    check(std::integral_constant<int, 8>{}, 1e-3);
}

TEST_CASE("the canonical polynomials' roots, a point far out included", "[methods][msm]") {
    // (z - r1) .. (z - rn) times a scale, in double, rounded to float coefficients.
    const auto coefficients = [](std::vector<double> roots, double scale) {
        std::vector<double> c{scale};
        for (const double r : roots) {
            c.push_back(0.0);
            for (std::size_t k = c.size() - 1; k > 0; --k) c[k] = c[k - 1] - r * c[k];
            c[0] = -r * c[0];
        }
        return std::vector<float>(c.begin(), c.end());
    };
    const auto check = [&]<int n>(std::integral_constant<int, n>, std::vector<double> roots, double tolerance) {
        const auto c = coefficients(roots, 2.5);
        const auto found = detail::real_roots<n>(c.data());
        std::sort(roots.begin(), roots.end());
        for (int i = 0; i < n; ++i) {
            CAPTURE(n, i, roots[std::size_t(i)], found[std::size_t(i)]);
            CHECK(found[std::size_t(i)] == Approx(roots[std::size_t(i)]).margin(tolerance).epsilon(1e-5));
        }
    };
    check(std::integral_constant<int, 3>{}, {-0.7, 0.1, 0.9}, 1e-5);
    check(std::integral_constant<int, 4>{}, {-0.95, -0.3, 0.2, 0.8}, 1e-5);
    // One root far out: c_n small beside the rest, where Viete's and Ferrari's forms lose the others.
    check(std::integral_constant<int, 3>{}, {-0.5, 0.25, 4000.0}, 1e-5);
    check(std::integral_constant<int, 4>{}, {-5000.0, -0.6, 0.3, 0.7}, 1e-5);
    check(std::integral_constant<int, 4>{}, {-0.9, -0.1, 0.4, 2.0e5}, 1e-4);
}

TEST_CASE("the moment bound: overestimation 0 never above the exact optical depth, 1 never below it", "[methods][msm]") {
    const auto check_bounds = []<int M>(std::integral_constant<int, M>, const hair_model& model, const light_space& light, const raster_options& options,
                                        std::size_t queries_at_least) {
        const auto fragments = rasterize(model, light, options);
        const deep_shadow_map exact(fragments, light);
        auto lower = with_overestimation<M>(0.0f), upper = with_overestimation<M>(1.0f);
        lower.build(model, light, options);
        upper.build(model, light, options);
        std::size_t queries = 0, below = 0, above = 0;
        double worst_low = 0, worst_high = 0;
        for (int y = 0; y < light.resolution(); ++y)
            for (int x = 0; x < light.resolution(); ++x)
                for (const auto& f : fragments.texel(x, y)) {
                    // Just behind each fragment, where the exact map counts it: the upper bound's
                    // point at the query then holds no fragment of its own.
                    const float depth = std::nextafter(f.depth, 2.0f);
                    const float tau = exact.optical_depth(x, y, depth);
                    const float low = lower.optical_depth(x, y, depth), high = upper.optical_depth(x, y, depth);
                    const float total = lower.stored_optical_depth(x, y, 0);
                    ++queries;
                    worst_low = std::max(worst_low, double(low - tau) / total);
                    worst_high = std::max(worst_high, double(tau - high) / total);
                    below += low <= tau + 1e-3f * total;
                    above += high >= tau - 1e-3f * total;
                }
        CAPTURE(M, queries, worst_low, worst_high);
        CHECK(queries >= queries_at_least);
        CHECK(below == queries);
        CHECK(above == queries);
    };
    SECTION("five sheets") {
        const auto scene = test::make_sheets(5, 64);
        check_bounds(std::integral_constant<int, 4>{}, scene.model, scene.light, test::alpha(0.3f), 1000);
        check_bounds(std::integral_constant<int, 6>{}, scene.model, scene.light, test::alpha(0.3f), 1000);
        check_bounds(std::integral_constant<int, 8>{}, scene.model, scene.light, test::alpha(0.3f), 1000);
    }
    SECTION("Sintel, 128x128") {
        const auto m = read_tfx(test::sintel_hair());
        const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 128);
        check_bounds(std::integral_constant<int, 4>{}, m, light, {}, 100000);
        check_bounds(std::integral_constant<int, 6>{}, m, light, {}, 100000);
        check_bounds(std::integral_constant<int, 8>{}, m, light, {}, 100000);
    }
}

TEST_CASE("msm specs parse the overestimation, and refuse bad ones", "[methods][msm][spec]") {
    const auto map = make_shadow_map("msm:4:0");
    const auto* made = map->method_if<moment_shadow_maps<4>>();
    REQUIRE(made != nullptr);
    CHECK(made->reconstruction().parameters().overestimation == 0.0f);
    CHECK(make_shadow_map("msm")->method_if<moment_shadow_maps<4>>()->reconstruction().parameters() == power_moments_parameters{});
    const auto eight = make_shadow_map("msm:8:1");
    REQUIRE(eight->method_if<moment_shadow_maps<8>>() != nullptr);
    CHECK(eight->method_if<moment_shadow_maps<8>>()->reconstruction().parameters().overestimation == 1.0f);
    CHECK(make_shadow_map("msm:6")->method_if<moment_shadow_maps<6>>() != nullptr);
    // No bias, or too little: a texel of two depths would leave the moments' matrix singular.
    CHECK_THROWS_AS(power_moments<4>({.bias = 0.0f}), argument_error);
    CHECK_THROWS_AS(power_moments<8>({.bias = 1e-9f}), argument_error);
    CHECK_THROWS_AS(power_moments<4>({.overestimation = std::nanf("")}), argument_error);
    for (const char* bad : {"msm:", "msm:5", "msm:10", "msm:2", "msm:04", "msm:4:1.5", "msm:4:-0.1", "msm:4:nan", "msm:4:0:1", "msm:4:8bit", "msm:x"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
}

TEST_CASE("msm maps build tile by tile as from fragments, for any thread count, and through the registry", "[methods][msm][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    CHECK(test::same_maps_tiled_and_buffered(moment_shadow_maps<>(), m, fb, light));
    CHECK(test::same_maps_tiled_and_buffered(moment_shadow_maps<8>(), m, fb, light));

    const auto map = make_shadow_map("msm:4:0.5");
    map->build(m, light);
    auto direct = with_overestimation(0.5f);
    direct.build(m, light);
    CHECK(test::same_transmittance(*map, direct, m));
    const auto eight = make_shadow_map("msm:8:0.5");
    eight->build(m, light);
    auto direct_eight = with_overestimation<8>(0.5f);
    direct_eight.build(m, light);
    CHECK(test::same_transmittance(*eight, direct_eight, m));
}
