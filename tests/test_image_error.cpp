// The image error (shading/image_error.hpp), the hair's coverage and supersampled renders: a
// hand-computed difference of constructed images, and renders of sheets of strands.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace hairshadow;

TEST_CASE("the image error is the mean and 99th percentile of |sRGB difference| over hair pixels", "[shading][image_error]") {
    // 200 pixels, 100 of them hair. Linear 0.5 is sRGB 188/255 and linear 0.25 is 137/255; 60 hair
    // pixels differ in one channel by 51 steps, 40 not at all; the other 100 differ in every channel
    // but are not hair.
    image a(20, 10, glm::vec3(0.5f)), b(20, 10, glm::vec3(0.5f));
    std::vector<float> coverage(200, 0.0f);
    for (int i = 0; i < 100; ++i) coverage[std::size_t(i)] = i % 2 ? 1.0f : 0.25f;
    for (int i = 0; i < 60; ++i) b.pixels[std::size_t(i)].g = 0.25f;
    for (int i = 100; i < 200; ++i) b.pixels[std::size_t(i)] = glm::vec3(0.0f);
    REQUIRE(int(image::encode(0.5f)) - int(image::encode(0.25f)) == 51);
    const auto d = image_error(a, b, coverage);
    CHECK(d.pixels == 100);
    CHECK(d.mean == Approx(0.6 * 51.0 / (3.0 * 255.0)));
    CHECK(d.p99 == Approx(51.0 / (3.0 * 255.0)));
    CHECK(image_error(a, b, std::vector<float>(200, 0.0f)).pixels == 0);
    CHECK_THROWS_AS(image_error(a, b, std::vector<float>(10)), argument_error);
}

TEST_CASE("renders of sheets: the hair's coverage, supersampling, and the shadow the image error sees", "[shading][image_error]") {
    const auto sheets = test::make_sheets(3, 64);
    scene sc;
    sc.hair = sheets.model;
    sc.lights.push_back({light_spec::directional({0, 0, -1}), glm::vec3(1.0f)});
    const auto light = light_space::fit(sc.lights[0].spec, sc.bounds(), 64);
    raster_options ro;
    ro.fixed_alpha = 0.4f;
    const auto fragments = rasterize(sc.hair, light, ro);
    const deep_shadow_map exact(fragments, light);
    // Seen from behind the sheets (the light's far side), through the gaps between the rows.
    const auto cam = camera::framing(sc.bounds(), 180.0f, 0.0f, 64, 64, 1.0f);
    render_options options;
    std::vector<float> coverage(64 * 64);
    const std::vector<lit_light> unshadowed{{sc.lights[0], {}, {}}}, shadowed{{sc.lights[0], query_of(exact), {}}};
    const image plain = render_cpu(sc, cam, unshadowed, options, coverage);
    const image with_shadow = render_cpu(sc, cam, shadowed, options);
    std::size_t hair = 0;
    for (float c : coverage) {
        hair += c > 0.0f;
        CHECK((c >= 0.0f && c <= 1.0f));
    }
    CHECK(hair > 200);
    CHECK(hair < coverage.size());
    // The back sheet, which the camera sees first, lies behind two sheets: T = 0.36 for its diffuse
    // and specular light, so the shadow darkens hair pixels by a clear margin, and nothing else.
    const auto d = image_error(plain, with_shadow, coverage);
    CHECK(d.mean > 0.05);
    std::vector<float> background(coverage.size());
    for (std::size_t i = 0; i < coverage.size(); ++i) background[i] = coverage[i] > 0.0f ? 0.0f : 1.0f;
    CHECK(image_error(plain, with_shadow, background).mean == 0.0);

    // A known image: with no ambient light and a black background every hair pixel's linear value is
    // its light times the transmittance, so a transmittance of 1/2 everywhere halves each one
    // exactly; the image error is then the sRGB difference of each value from its half.
    scene dark = sc;
    dark.material.ambient = 0.0f;
    dark.background = glm::vec3(0.0f);
    const transmittance_query half = [](std::span<const glm::vec3>, std::span<float> out) { std::fill(out.begin(), out.end(), 0.5f); };
    const std::vector<lit_light> full_light{{dark.lights[0], {}, {}}}, half_light{{dark.lights[0], half, {}}};
    std::vector<float> dark_coverage(64 * 64);
    const image lit = render_cpu(dark, cam, full_light, options, dark_coverage);
    const image halved = render_cpu(dark, cam, half_light, options);
    double expected = 0.0;
    std::size_t pixels = 0;
    for (std::size_t i = 0; i < lit.pixels.size(); ++i) {
        if (!(dark_coverage[i] > 0.0f)) continue;
        ++pixels;
        for (int c = 0; c < 3; ++c) {
            CHECK(halved.pixels[i][c] == 0.5f * lit.pixels[i][c]);
            expected += std::abs(int(image::encode(lit.pixels[i][c])) - int(image::encode(0.5f * lit.pixels[i][c]))) / (3.0 * 255.0);
        }
    }
    const auto known = image_error(lit, halved, dark_coverage);
    CHECK(known.pixels == pixels);
    CHECK(known.mean == Approx(expected / double(pixels)));
    CHECK(known.mean > 0.05);

    // Supersampled: the same picture averaged from 3x3 samples a pixel, with fractional coverage at
    // the strands' edges where one sample a pixel gives whole pixels.
    options.supersample = 3;
    std::vector<float> smooth_coverage(64 * 64);
    const image smooth = render_cpu(sc, cam, shadowed, options, smooth_coverage);
    CHECK(smooth.width == 64);
    CHECK(smooth.height == 64);
    std::size_t partial = 0;
    for (float c : smooth_coverage) partial += c > 0.01f && c < 0.99f;
    CHECK(partial > 50);
    options.supersample = 9;
    CHECK_THROWS_AS(render_cpu(sc, cam, shadowed, options), argument_error);
}
