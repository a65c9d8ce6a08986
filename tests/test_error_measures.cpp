// The point error (reference/point_error.hpp) and the error over an animation with its flicker
// (reference/temporal_error.hpp), against hand-computed values: the measures that compare, the figure
// and animate print.
#include <hairshadow/reference/point_error.hpp>
#include <hairshadow/reference/temporal_error.hpp>

#include <catch2/catch.hpp>

#include <vector>

using namespace hairshadow;

TEST_CASE("the point error is the mean, 95th percentile and maximum of |T - T_exact|", "[methods][error]") {
    // 100 points whose errors are 0.005 k for k = 0..99, alternately above and below the exact value
    // and in no order: mean 0.2475, the 95th percentile the error at rank 95 (0.475), the largest 0.495.
    std::vector<float> t, exact;
    for (int i = 0; i < 100; ++i) {
        const int k = (i * 37) % 100; // a permutation of 0..99
        exact.push_back(0.5f);
        t.push_back(k % 2 ? 0.5f + 0.005f * float(k) : 0.5f - 0.005f * float(k));
    }
    const auto e = point_error_of(t, exact);
    CHECK(e.points == 100);
    CHECK(e.mean == Approx(0.2475).epsilon(1e-6));
    CHECK(e.p95 == Approx(0.475).epsilon(1e-6));
    CHECK(e.max == Approx(0.495).epsilon(1e-6));
    // Fewer than 20 points: the 95th percentile is the largest error.
    const std::vector<float> three{0.1f, 0.7f, 0.4f}, exact3{0.2f, 0.5f, 0.4f};
    const auto small = point_error_of(three, exact3);
    CHECK(small.mean == Approx(0.1).epsilon(1e-6));
    CHECK(small.p95 == Approx(0.2).epsilon(1e-6));
    CHECK(small.max == Approx(0.2).epsilon(1e-6));
    CHECK(point_error_of({}, {}).points == 0);
    CHECK_THROWS_AS(point_error_of(three, std::vector<float>(2)), argument_error);
}

TEST_CASE("the flicker is the mean change of the error between frames, the last to the first included", "[methods][error][animate]") {
    // Two points over three frames; e = T - T_exact:
    //   frame 0: e = ( 0.1,  0.0)
    //   frame 1: e = (-0.1,  0.3)
    //   frame 2: e = ( 0.0, -0.2)
    // mean |e| = (0.1 + 0 + 0.1 + 0.3 + 0 + 0.2) / 6 = 0.7 / 6;
    // |e(t+1) - e(t)|: frames 0 to 1: 0.2 + 0.3; 1 to 2: 0.1 + 0.5; the loop's 2 to 0: 0.1 + 0.2; so
    // the flicker is 1.4 over 3 pairs of 2 points, 1.4 / 6 (without the loop's pair it would be 1.1 / 4).
    temporal_error errors;
    CHECK(errors.mean_error() == 0.0);
    CHECK(errors.flicker() == 0.0);
    errors.add_frame(std::vector<float>{0.5f, 0.2f}, std::vector<float>{0.4f, 0.2f});
    CHECK(errors.mean_error() == Approx(0.1 / 2).epsilon(1e-6));
    CHECK(errors.flicker() == 0.0); // one frame: no pair
    errors.add_frame(std::vector<float>{0.3f, 0.5f}, std::vector<float>{0.4f, 0.2f});
    errors.add_frame(std::vector<float>{0.4f, 0.2f}, std::vector<float>{0.4f, 0.4f});
    CHECK(errors.frames() == 3);
    CHECK(errors.mean_error() == Approx(0.7 / 6).epsilon(1e-6));
    CHECK(errors.flicker() == Approx(1.4 / 6).epsilon(1e-6));
    // Two frames: the pair counts both ways, so the flicker is the one change.
    temporal_error two;
    two.add_frame(std::vector<float>{0.5f}, std::vector<float>{0.5f});
    two.add_frame(std::vector<float>{0.8f}, std::vector<float>{0.5f});
    CHECK(two.flicker() == Approx(0.3).epsilon(1e-6));
    CHECK_THROWS_AS(two.add_frame(std::vector<float>{0.5f, 0.5f}, std::vector<float>{0.5f, 0.5f}), argument_error);
    CHECK_THROWS_AS(two.add_frame(std::vector<float>{0.5f}, std::vector<float>{0.5f, 0.5f}), argument_error);
}
