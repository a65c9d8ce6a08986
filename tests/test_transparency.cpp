// Transparent hair (Sintorn & Assarsson 3.4): exact blending follows the blending equation;
// occupancy-ordered blending is exact where every fragment of a pixel has a slice of its own, and on
// the Sintel model it is closer to exact blending than weighted-average blending is.
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/shading/transparency.hpp>

#include <catch2/catch.hpp>

using namespace hairshadow;

namespace {
/// One row of pixels, pixel i holding `frags[i]`.
camera_fragments row_of(const std::vector<std::vector<camera_fragment>>& frags) {
    camera_fragments f;
    f.width = f.height = int(frags.size());
    f.offsets.assign(frags.size() * frags.size() + 1, 0);
    for (std::size_t i = 0; i < frags.size(); ++i) {
        f.fragments.insert(f.fragments.end(), frags[i].begin(), frags[i].end());
        f.offsets[i + 1] = f.fragments.size();
    }
    for (std::size_t i = frags.size() + 1; i < f.offsets.size(); ++i) f.offsets[i] = f.fragments.size();
    return f;
}
} // namespace

TEST_CASE("exact blending follows the blending equation, back to front", "[transparency]") {
    const glm::vec3 r(1, 0, 0), g(0, 1, 0), b(0, 0, 1), background(0.5f, 0.5f, 0.5f);
    // Drawn out of order: depths 0.5, 0.2, 0.8.
    const auto f = row_of({{{0.5f, 0.5f, g}, {0.2f, 0.3f, r}, {0.8f, 0.2f, b}}});
    image out(1, 1, background);
    blend_fragments(out, f, transparency::exact);
    const glm::vec3 expected = 0.3f * r + 0.7f * (0.5f * g + 0.5f * (0.2f * b + 0.8f * background));
    for (int c = 0; c < 3; ++c) CHECK(out.pixels[0][c] == Approx(expected[c]).margin(1e-6));
    image opaque(1, 1, background);
    blend_fragments(opaque, f, transparency::none);
    CHECK(opaque.pixels[0] == r); // the nearest
    image weighted(1, 1, background);
    blend_fragments(weighted, f, transparency::weighted); // mean colour (alpha-weighted), mean alpha three times
    const glm::vec3 mean = (0.3f * r + 0.5f * g + 0.2f * b) / 1.0f;
    const float behind = std::pow(1.0f - 1.0f / 3.0f, 3.0f);
    for (int c = 0; c < 3; ++c) CHECK(weighted.pixels[0][c] == Approx(mean[c] * (1 - behind) + behind * background[c]).margin(1e-6));
    // Of equal depths (where a strand's segments meet) the first drawn is in front, as opaque hair
    // shows it and as GL's depth peeling blends it.
    image tied(1, 1, background);
    blend_fragments(tied, row_of({{{0.4f, 0.5f, r}, {0.4f, 0.5f, g}}}), transparency::exact);
    const glm::vec3 r_in_front = 0.5f * r + 0.5f * (0.5f * g + 0.5f * background);
    for (int c = 0; c < 3; ++c) CHECK(tied.pixels[0][c] == Approx(r_in_front[c]).margin(1e-6));
}

TEST_CASE("occupancy-ordered blending is exact where each fragment has a slice of its own", "[transparency]") {
    random_stream rng(7);
    std::vector<std::vector<camera_fragment>> pixels(24);
    for (auto& p : pixels) {
        // Distinct slices of the pixel's range: slice centres of a random subset of the 128 slices,
        // the first and last slice included so that the range is known.
        const int n = 2 + int(rng.next() % 40);
        std::vector<int> slices{0, 127};
        while (int(slices.size()) < n) {
            const int s = int(rng.next() % 128);
            if (std::find(slices.begin(), slices.end(), s) == slices.end()) slices.push_back(s);
        }
        for (std::size_t k = slices.size() - 1; k > 0; --k) std::swap(slices[k], slices[rng.next() % (k + 1)]); // drawing order
        for (int s : slices) {
            const float depth = s == 0 ? 0.2f : s == 127 ? 0.6f : 0.2f + 0.4f * (float(s) + 0.5f) / 128.0f;
            p.push_back({depth, 0.15f, glm::vec3(rng.uniform(), rng.uniform(), rng.uniform())});
        }
    }
    const auto f = row_of(pixels);
    image exact(f.width, f.height, glm::vec3(0.2f)), ordered = exact;
    blend_fragments(exact, f, transparency::exact);
    blend_fragments(ordered, f, transparency::occupancy);
    for (std::size_t i = 0; i < pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) CHECK(ordered.pixels[i][c] == Approx(exact.pixels[i][c]).margin(2e-5));
    // The same pixels as wide and tall images (each pixel's maps are its own, so each pixel blends
    // alike): the maps are square, the image need not be.
    for (const auto& [w, h] : {std::pair(24, 1), std::pair(6, 4), std::pair(4, 6), std::pair(1, 24)}) {
        CAPTURE(w, h);
        camera_fragments shaped = f;
        shaped.width = w;
        shaped.height = h;
        shaped.offsets.resize(pixels.size() + 1);
        image out(w, h, glm::vec3(0.2f));
        blend_fragments(out, shaped, transparency::occupancy);
        for (std::size_t i = 0; i < pixels.size(); ++i) CHECK(out.pixels[i] == ordered.pixels[i]);
    }
    // And they are not trivially equal: drawing order alone would differ.
    image weighted(f.width, f.height, glm::vec3(0.2f));
    blend_fragments(weighted, f, transparency::weighted);
    double differs = 0;
    for (std::size_t i = 0; i < pixels.size(); ++i) differs += std::abs(weighted.pixels[i].x - exact.pixels[i].x);
    CHECK(differs / double(pixels.size()) > 0.01);
}

TEST_CASE("on the Sintel model occupancy-ordered blending is closer to exact than weighted averages", "[transparency][sintel]") {
    scene sc;
    sc.hair = read_tfx(test::sintel_hair());
    sc.lights = {{light_spec::directional({-0.7f, -0.9f, -0.45f}), glm::vec3(1.1f)}};
    const auto space = light_space::fit(sc.lights[0].spec, sc.bounds(), 256);
    occupancy_maps<128, 4> shadows;
    shadows.build(rasterize(sc.hair, space), space);
    const std::vector<lit_light> lights{{sc.lights[0], query_of(shadows), {}}};
    const auto cam = camera::framing(sc.bounds(), 25.0f, 10.0f, 256, 256, 1.15f);
    std::vector<image> images;
    for (auto mode : {transparency::exact, transparency::occupancy, transparency::weighted, transparency::none})
        images.push_back(render_transparent(sc, cam, lights, mode, 0.4f));
    const double occupancy_error = mean_absolute_difference(images[1], images[0]);
    const double weighted_error = mean_absolute_difference(images[2], images[0]);
    const double opaque_error = mean_absolute_difference(images[3], images[0]);
    CAPTURE(occupancy_error, weighted_error, opaque_error);
    CHECK(occupancy_error < 0.01);
    CHECK(occupancy_error < 0.5 * weighted_error);
    CHECK(occupancy_error < 0.5 * opaque_error); // and than opaque hair
}
