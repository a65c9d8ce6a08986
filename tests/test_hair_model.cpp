#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <limits>

using namespace hairshadow;

TEST_CASE("a model counts strands, points and segments and knows its bounds", "[model]") {
    auto m = test::grid_model(4, 5);
    m.add_strand(std::vector<glm::vec3>{{9, 9, 9}}); // one point, no segment
    CHECK(m.strand_count() == 5);
    CHECK(m.point_count() == 21);
    CHECK(m.segment_count() == 16);
    const auto b = m.bounds();
    CHECK(b.min == glm::vec3(0, -0.2f, 0));
    CHECK(b.max == glm::vec3(9, 9, 9));
    CHECK_NOTHROW(validate(m));
}

TEST_CASE("validation rejects models that break an invariant", "[model]") {
    SECTION("no strands") {
        hair_model m;
        CHECK_THROWS_AS(validate(m), model_error);
    }
    SECTION("a non-finite coordinate") {
        auto m = test::grid_model(2, 3);
        m.points[4].y = std::numeric_limits<float>::quiet_NaN();
        CHECK_THROWS_WITH(validate(m), Catch::Contains("point 4") && Catch::Contains("non-finite"));
        m.points[4].y = std::numeric_limits<float>::infinity();
        CHECK_THROWS_AS(validate(m), model_error);
    }
    SECTION("only zero-length segments") {
        hair_model m;
        m.add_strand(std::vector<glm::vec3>{{1, 1, 1}, {1, 1, 1}});
        CHECK_THROWS_WITH(validate(m), Catch::Contains("no segment of non-zero length"));
    }
    SECTION("a per-point array of the wrong size") {
        auto m = test::grid_model(2, 3);
        m.thickness.assign(5, 0.1f);
        CHECK_THROWS_WITH(validate(m), Catch::Contains("thickness array has 5 values for 6 points"));
    }
    SECTION("transparency outside [0, 1] or negative thickness") {
        auto m = test::grid_model(2, 3);
        m.transparency.assign(6, 0.5f);
        m.transparency[2] = 1.5f;
        CHECK_THROWS_AS(validate(m), model_error);
        m.transparency.clear();
        m.default_thickness = -1.0f;
        CHECK_THROWS_AS(validate(m), model_error);
    }
    SECTION("offsets that do not cover the points") {
        auto m = test::grid_model(2, 3);
        m.points.emplace_back(0, 0, 0);
        CHECK_THROWS_AS(validate(m), model_error);
    }
}

TEST_CASE("a model without thickness gets one from its size", "[model]") {
    auto m = test::grid_model(3, 3);
    m.default_thickness = 0.0f;
    ensure_thickness(m);
    CHECK(m.default_thickness == Approx(m.bounds().diagonal() / 5000.0f));
}
