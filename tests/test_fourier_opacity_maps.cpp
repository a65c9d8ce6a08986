// Fourier opacity maps (fom:C): the coefficients and the reconstructed transmittance behind sheets of
// strands at known depths, worked by hand in double from Jansen & Bavoil's formulas; the ringing
// between two sheets and what the sigma factors do to it; the 8-bit variant's steps by hand and
// within their rounding of the float maps; specs; and the builds every method shares (tiled against
// buffered, any thread count, the registry).
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace hairshadow;

namespace {

/// The paper's series by hand, in double: spikes of optical depth b at periods' positions t.
struct hand_series {
    int harmonics;
    bool damped;
    std::vector<double> a; // a_0, a_1, b_1, a_2, b_2, ...

    hand_series(const std::vector<double>& t, double b, int n, bool sigma) : harmonics(n), damped(sigma) {
        a.push_back(2.0 * b * double(t.size()));
        for (int k = 1; k <= n; ++k) {
            double ak = 0, bk = 0;
            for (const double ti : t) ak += 2 * b * std::cos(2 * std::numbers::pi * k * ti), bk += 2 * b * std::sin(2 * std::numbers::pi * k * ti);
            a.push_back(ak);
            a.push_back(bk);
        }
    }
    double tau(double t) const {
        double r = a[0] * t / 2;
        for (int k = 1; k <= harmonics; ++k) {
            const double x = std::numbers::pi * k / (harmonics + 1), sigma = damped ? std::sin(x) / x : 1.0;
            r += sigma * (a[std::size_t(2 * k - 1)] * std::sin(2 * std::numbers::pi * k * t) + a[std::size_t(2 * k)] * (1 - std::cos(2 * std::numbers::pi * k * t))) /
                 (2 * std::numbers::pi * k);
        }
        return r;
    }
};

} // namespace

TEST_CASE("Fourier opacity maps store the paper's coefficients and give its series' transmittance behind sheets of strands", "[methods][fom]") {
    // Five sheets at z = 0.5 .. -0.3, every fragment of alpha 0.3: each texel's range runs from the
    // first sheet to the last, which map onto [m, 1 - m] of the period.
    const auto scene = test::make_sheets(5, 64);
    const double b = -std::log(0.7);
    const float y = scene.row_y[scene.row_y.size() / 2];
    for (const bool damped : {false, true}) {
        CAPTURE(damped);
        fourier_opacity_maps<7> fom{depth_range<1>(), fourier_series<7>(damped)};
        fom.build(scene.model, scene.light, test::alpha(0.3f));
        const float near = test::depth_at(scene, 0.5f), far = test::depth_at(scene, -0.3f);
        // The range's margin in the period: 1/7, damped 1/7 + 1/8 (the sigma factors' wider lobe).
        const double m = damped ? 1.0 / 7.0 + 1.0 / 8.0 : 1.0 / 7.0;
        CHECK(fom.reconstruction().margin() == Approx(m).epsilon(1e-7));
        const auto period = [&](float depth) { return m + (1 - 2 * m) * (double(depth) - near) / (double(far) - near); };
        std::vector<double> t;
        for (const float z : scene.sheet_z) t.push_back(period(test::depth_at(scene, z)));
        const hand_series hand(t, b, 3, damped);
        for (int k = 0; k < 7; ++k) {
            CAPTURE(k);
            CHECK(fom.stored_optical_depth(32, 32, k) == Approx(hand.a[std::size_t(k)]).margin(1e-5 * hand.a[0]));
        }
        // Nothing in front of the first sheet nor on it; all five behind the last.
        CHECK(fom.transmittance(glm::vec3(0.2f, y, 0.9f)) == 1.0f);
        CHECK(fom.transmittance(glm::vec3(0.2f, y, 0.5f)) == 1.0f);
        CHECK(fom.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(std::pow(0.7, 5)).epsilon(1e-5));
        // Between: exp(-tau(t)), tau held within [0, total].
        for (const float z : {0.49f, 0.4f, 0.3f, 0.25f, 0.1f, -0.05f, -0.2f, -0.29f}) {
            CAPTURE(z);
            const double tau = std::clamp(hand.tau(period(test::depth_at(scene, z))), 0.0, 5 * b);
            CHECK(fom.transmittance(glm::vec3(0.2f, y, z)) == Approx(std::exp(-tau)).epsilon(2e-5));
        }
        // The series is not the staircase: just behind the first sheet, part of its own shadow (0.41
        // of it undamped, 0.56 damped: a spike's series spreads to both sides of it), and between
        // sheets, within half a sheet of the exact.
        const float just_behind = fom.transmittance(glm::vec3(0.2f, y, 0.4999f));
        CHECK(just_behind < std::pow(0.7f, 0.35f));
        CHECK(just_behind > std::pow(0.7f, 0.6f));
        for (int k = 1; k < 5; ++k) {
            const float between = 0.5f * (scene.sheet_z[std::size_t(k - 1)] + scene.sheet_z[std::size_t(k)]);
            CHECK(std::abs(std::log(fom.transmittance(glm::vec3(0.2f, y, between))) / std::log(0.7) - k) < 0.5);
        }
    }
}

TEST_CASE("Fourier opacity maps ring between two sheets, and the sigma factors damp the ringing", "[methods][fom]") {
    // Two sheets, at the ends of the range: the undamped series falls back by 0.28 of a sheet's
    // optical depth on its way from one to the other (the Gibbs overshoot), the damped one by 0.03.
    const auto scene = test::make_sheets(2, 64);
    const float y = scene.row_y[scene.row_y.size() / 2];
    const auto largest_fall = [&](bool damped) {
        fourier_opacity_maps<7> fom{depth_range<1>(), fourier_series<7>(damped)};
        fom.build(scene.model, scene.light, test::alpha(0.3f));
        double highest = 0, fall = 0;
        for (int i = 1; i < 200; ++i) {
            const float z = 0.5f - 0.2f * float(i) / 200.0f;
            const double tau = -std::log(double(fom.transmittance(glm::vec3(0.2f, y, z)))) / -std::log(0.7);
            highest = std::max(highest, tau);
            fall = std::max(fall, highest - tau);
        }
        return fall;
    };
    CHECK(largest_fall(false) == Approx(0.277).margin(0.01));
    CHECK(largest_fall(true) == Approx(0.0275).margin(0.01));
}

TEST_CASE("fom specs parse C and sigma, and refuse bad ones", "[methods][fom][spec]") {
    const auto map = make_shadow_map("fom:7:sigma");
    const auto* made = map->method_if<fourier_opacity_maps<7>>();
    REQUIRE(made != nullptr);
    CHECK(made->reconstruction().damped());
    CHECK_FALSE(make_shadow_map("fom")->method_if<fourier_opacity_maps<7>>()->reconstruction().damped());
    CHECK(make_shadow_map("fom:15")->method_if<fourier_opacity_maps<15>>() != nullptr);
    CHECK(make_shadow_map("fom:3")->method_if<fourier_opacity_maps<3>>() != nullptr);
    CHECK(make_shadow_map("fom:7:8bit")->method_if<fourier_opacity_maps<7, emulated_8bit>>() != nullptr);
    const auto damped_eight = make_shadow_map("fom:15:sigma:8bit");
    REQUIRE(damped_eight->method_if<fourier_opacity_maps<15, emulated_8bit>>() != nullptr);
    CHECK(damped_eight->method_if<fourier_opacity_maps<15, emulated_8bit>>()->reconstruction().damped());
    for (const char* bad : {"fom:", "fom:4", "fom:9", "fom:07", "fom:7:damped", "fom:7:sigma:1", "fom:sigma", "fom:8bit:7", "fom:7:8bit:sigma", "fom:17"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
}

TEST_CASE("fom maps build tile by tile as from fragments, for any thread count, and through the registry", "[methods][fom][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    CHECK(test::same_maps_tiled_and_buffered(fourier_opacity_maps<7>(), m, fb, light));
    CHECK(test::same_maps_tiled_and_buffered(fourier_opacity_maps<15>(depth_range<1>(), fourier_series<15>(true)), m, fb, light));

    CHECK(test::same_maps_tiled_and_buffered(fourier_opacity_maps<7, emulated_8bit>(), m, fb, light));

    const auto map = make_shadow_map("fom:11:sigma");
    map->build(m, light);
    fourier_opacity_maps<11> direct(depth_range<1>(), fourier_series<11>(true));
    direct.build(m, light);
    CHECK(test::same_transmittance(*map, direct, m));
    const auto eight = make_shadow_map("fom:7:8bit");
    eight->build(m, light);
    fourier_opacity_maps<7, emulated_8bit> direct_eight;
    direct_eight.build(m, light);
    CHECK(test::same_transmittance(*eight, direct_eight, m));
}

TEST_CASE("8-bit Fourier opacity maps store each term's steps, within their rounding of the float maps", "[methods][fom][8bit]") {
    SECTION("two sheets, by hand") {
        // alpha 0.3: b = 0.3567, one step of kappa / 255 = 0.02175 is 16.4, rounded to 16 a sheet.
        const auto scene = test::make_sheets(2, 64);
        fourier_opacity_maps<7, emulated_8bit> eight;
        eight.build(scene.model, scene.light, test::alpha(0.3f));
        const auto& steps = eight.texel(32, 32).data.sums;
        CHECK(int(steps[0]) == 32);
        // The sheets sit at the period's t = m and 1 - m (m = 1/7): cos(2 pi k t) is the same at both,
        // sin opposite, so a_k's steps are 2 round(16.4 (1 + cos) / 2) and b_k's
        // round(16.4 (1 + sin) / 2) + round(16.4 (1 - sin) / 2).
        const double b = -std::log(0.7), t = 1.0 / 7.0;
        for (int k = 1; k <= 3; ++k) {
            const double c = std::cos(2 * std::numbers::pi * k * t), sn = std::sin(2 * std::numbers::pi * k * t);
            const auto level = [&](double e) { return std::lround(e / emulated_8bit::kappa * 255.0); };
            CAPTURE(k);
            CHECK(int(steps[std::size_t(2 * k - 1)]) == 2 * level(b * (1 + c) / 2));
            CHECK(int(steps[std::size_t(2 * k)]) == level(b * (1 + sn) / 2) + level(b * (1 - sn) / 2));
        }
        // Behind both sheets, the stored total: 32 steps.
        const float y = scene.row_y[scene.row_y.size() / 2];
        CHECK(eight.transmittance(glm::vec3(0.2f, y, -0.9f)) == Approx(std::exp(-emulated_8bit::kappa * 32.0f / 255.0f)).epsilon(1e-6));
        CHECK(eight.transmittance(glm::vec3(0.2f, y, 0.9f)) == 1.0f);
    }
    SECTION("Sintel: every sum within its steps' rounding") {
        const auto m = read_tfx(test::sintel_hair());
        const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
        const auto fb = rasterize(m, light);
        fourier_opacity_maps<7> full;
        fourier_opacity_maps<7, emulated_8bit> eight;
        full.build(m, light);
        eight.build(m, light);
        CHECK(eight.memory_bytes() < full.memory_bytes() / 2);
        // n fragments: the total's steps are each within half a level (n / 2 levels), a_k = 2 (2 S_k - B)
        // within 2 (n + n / 2) levels.
        const float level = emulated_8bit::kappa / 255.0f;
        long checked = 0, saturated = 0, off = 0;
        double worst = 0;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const auto n = float(fb.texel(x, y).size());
                if (n == 0) continue;
                if (eight.texel(x, y).data.sums[0] == 255) {
                    ++saturated; // the total's steps saturated, and every sum's with it
                    continue;
                }
                ++checked;
                for (int k = 0; k < 7; ++k) {
                    const float bound = (k == 0 ? n : 3.0f * n) * level, error = std::abs(eight.stored_optical_depth(x, y, k) - full.stored_optical_depth(x, y, k));
                    worst = std::max(worst, double(error / bound));
                    off += error > bound + 1e-5f;
                }
            }
        CAPTURE(checked, saturated, worst);
        CHECK(checked > 5000);
        CHECK(off == 0);
        CHECK(worst > 0.1); // the rounding is there to see
    }
}
