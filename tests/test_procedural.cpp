#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

using namespace hairshadow;

TEST_CASE("procedural models are sized by strand and segment counts and deterministic", "[procedural]") {
    const auto style = GENERATE(hair_style::straight, hair_style::wavy, hair_style::curly, hair_style::clumped);
    procedural_options o{.style = style, .strands = 300, .segments = 12, .seed = 42};
    const auto a = make_procedural(o);
    CHECK(a.strand_count() == 300);
    CHECK(a.segment_count() == 3600);
    CHECK_NOTHROW(validate(a));
    const auto b = make_procedural(o);
    CHECK(a.points == b.points);
    o.seed = 43;
    CHECK(make_procedural(o).points != a.points);
}

TEST_CASE("the styles differ in shape", "[procedural]") {
    auto make = [](hair_style s) { return make_procedural({.style = s, .strands = 50, .segments = 40, .seed = 5}); };
    const auto straight = make(hair_style::straight), wavy = make(hair_style::wavy), curly = make(hair_style::curly);
    // Same roots and centre lines, different offsets: the strands' points differ beyond the root.
    CHECK(straight.points[0] == wavy.points[0]);
    CHECK(straight.points[20] != wavy.points[20]);
    CHECK(curly.points[20] != wavy.points[20]);
    // Curly strands wind: their polyline is longer than the straight centre line.
    auto length = [](const hair_model& m) {
        float l = 0;
        for (std::size_t i = 1; i < m.strand_size(0); ++i) l += glm::length(m.strand(0)[i] - m.strand(0)[i - 1]);
        return l;
    };
    CHECK(length(curly) > 1.2f * length(straight));
}

TEST_CASE("the papers' model sizes can be made", "[procedural]") {
    CHECK(make_procedural({.strands = 10000, .segments = 16}).segment_count() == 160000);
    CHECK(make_procedural({.style = hair_style::curly, .strands = 10000, .segments = 150}).segment_count() == 1500000);
}

TEST_CASE("follow hair multiplies guides deterministically", "[procedural]") {
    const auto guides = make_procedural({.strands = 20, .segments = 15, .seed = 9});
    const auto grown = grow_follow_hair(guides, 8, 0.004f, 1);
    CHECK(grown.strand_count() == 160);
    CHECK(grown.segment_count() == 160 * 15);
    CHECK(grown.strand(8)[3] == guides.strand(1)[3]); // each group starts with its guide
    for (std::size_t k = 1; k < 8; ++k) {
        const float root_offset = glm::length(grown.strand(k)[0] - guides.strand(0)[0]);
        CHECK(root_offset <= 0.004f + 1e-6f);
    }
    CHECK(grow_follow_hair(guides, 8, 0.004f, 1).points == grown.points);
    CHECK_THROWS_AS(grow_follow_hair(guides, 0, 0.004f), argument_error);
}

TEST_CASE("procedural specs parse and reject bad input", "[procedural][errors]") {
    const auto o = parse_procedural_spec("procedural:curly:strands=123:segments=9:seed=4:length=0.3");
    CHECK(o.style == hair_style::curly);
    CHECK(o.strands == 123);
    CHECK(o.segments == 9);
    CHECK(o.seed == 4);
    CHECK(o.length == 0.3f);
    CHECK_THROWS_WITH(parse_procedural_spec("procedural:bald"), Catch::Contains("unknown style"));
    CHECK_THROWS_WITH(parse_procedural_spec("procedural:curly:strands=x"), Catch::Contains("not a valid number"));
    CHECK_THROWS_WITH(parse_procedural_spec("procedural:curly:colour=3"), Catch::Contains("unknown key"));
    CHECK_THROWS_AS(make_procedural(parse_procedural_spec("procedural:curly:strands=0")), argument_error);
    CHECK_THROWS_AS(make_procedural(parse_procedural_spec("procedural:curly:strands=4000000000:segments=60000")), argument_error);
    CHECK_THROWS_AS(parse_procedural_spec("procedural:curly:length=nan"), argument_error);
}

TEST_CASE("absurd procedural sizes are refused before any work", "[procedural][errors]") {
    CHECK_THROWS_AS(make_procedural(parse_procedural_spec("procedural:clumped:strands=100:clumps=10000000000")), argument_error);
    CHECK_THROWS_AS(make_procedural(parse_procedural_spec("procedural:clumped:strands=100:clumps=101")), argument_error);
    CHECK_NOTHROW(make_procedural(parse_procedural_spec("procedural:clumped:strands=100:clumps=100")));
    hair_model single_points;
    for (int i = 0; i < 1000; ++i) single_points.add_strand(std::vector<glm::vec3>{{float(i), 0, 0}});
    CHECK_THROWS_AS(grow_follow_hair(single_points, std::size_t(1) << 20, 0.01f), argument_error);
}

TEST_CASE("parallel loops survive absurd thread counts", "[parallel]") {
    std::vector<int> hits(1000, 0);
    parallel_for(hits.size(), execution{100000}, [&](std::size_t i) { hits[i] += 1; });
    CHECK(std::count(hits.begin(), hits.end(), 1) == 1000);
}
