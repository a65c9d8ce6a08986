#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <cstring>

using namespace hairshadow;

namespace {

/// Encodes a .hair file by hand with exactly the arrays in `fields`, independent of write_hair.
std::vector<unsigned char> encode_hair(const hair_model& m, std::uint32_t fields, std::uint32_t default_segments) {
    std::vector<unsigned char> b{'H', 'A', 'I', 'R'};
    test::append(b, std::uint32_t(m.strand_count()));
    test::append(b, std::uint32_t(m.point_count()));
    test::append(b, fields);
    test::append(b, default_segments);
    test::append(b, 0.25f);                  // default thickness
    test::append(b, 0.5f);                   // default transparency
    test::append(b, glm::vec3(0.1f, 0.2f, 0.3f)); // default colour
    b.resize(128, 0);
    if (fields & 1)
        for (std::size_t s = 0; s < m.strand_count(); ++s) test::append(b, std::uint16_t(m.strand_size(s) - 1));
    for (const auto& p : m.points) test::append(b, p);
    if (fields & 4)
        for (std::size_t i = 0; i < m.point_count(); ++i) test::append(b, float(i) * 0.01f);
    if (fields & 8)
        for (std::size_t i = 0; i < m.point_count(); ++i) test::append(b, float(i % 10) * 0.1f);
    if (fields & 16)
        for (std::size_t i = 0; i < m.point_count(); ++i) test::append(b, glm::vec3(float(i), 0.5f, 1.0f));
    return b;
}

} // namespace

TEST_CASE("every combination of optional .hair arrays reads back", "[io][hair]") {
    test::temp_dir dir("hair_combos");
    const auto m = test::grid_model(3, 4); // equal strand sizes, so the default segment count can stand in
    for (std::uint32_t optional = 0; optional < 16; ++optional) {
        // bit 0 of `optional` = segments array, bits 1..3 = thickness, transparency, colour
        const std::uint32_t fields = 2u | (optional & 1u) | ((optional & 14u) << 1);
        CAPTURE(fields);
        const auto path = dir.file("combo.hair");
        test::write_bytes(path, encode_hair(m, fields, 3));
        const auto r = read_hair(path);
        REQUIRE(r.strand_count() == 3);
        CHECK(r.points == m.points);
        CHECK(r.strand_offsets == m.strand_offsets);
        CHECK(r.default_transparency == 0.5f);
        CHECK(r.default_color == glm::vec3(0.1f, 0.2f, 0.3f));
        if (fields & 4) {
            REQUIRE(r.thickness.size() == 12);
            CHECK(r.thickness[7] == 0.07f);
        } else {
            CHECK(r.thickness.empty());
            CHECK(r.default_thickness == 0.25f);
            CHECK(r.thickness_at(5) == 0.25f);
        }
        if (fields & 8) {
            REQUIRE(r.transparency.size() == 12);
            CHECK(r.transparency[3] == 0.3f);
        } else {
            CHECK(r.transparency.empty());
            CHECK(r.transparency_at(3) == 0.5f);
        }
        if (fields & 16) {
            REQUIRE(r.colors.size() == 12);
            CHECK(r.colors[11] == glm::vec3(11, 0.5f, 1));
        } else {
            CHECK(r.colors.empty());
            CHECK(r.color_at(0) == glm::vec3(0.1f, 0.2f, 0.3f));
        }
    }
}

TEST_CASE("writing then reading .hair is lossless", "[io][hair]") {
    test::temp_dir dir("hair_roundtrip");
    auto m = make_procedural({.style = hair_style::curly, .strands = 50, .segments = 7, .seed = 3});
    m.add_strand(std::vector<glm::vec3>{{1, 2, 3}, {1, 2, 4}, {1, 3, 4}}); // a strand of another size
    const auto n = m.point_count();
    for (std::size_t i = 0; i < n; ++i) {
        m.thickness.push_back(0.001f * float(i % 7));
        m.transparency.push_back(float(i % 5) / 4.0f);
        m.colors.emplace_back(float(i) / float(n), 0.25f, 0.75f);
    }
    const auto path = dir.file("m.hair");
    write_hair(m, path);
    const auto r = read_hair(path);
    CHECK(r.points == m.points);
    CHECK(r.strand_offsets == m.strand_offsets);
    CHECK(r.thickness == m.thickness);
    CHECK(r.transparency == m.transparency);
    CHECK(r.colors == m.colors);
    CHECK(r.default_color == m.default_color);
}

TEST_CASE("malformed .hair files raise io_error naming the file", "[io][hair][errors]") {
    test::temp_dir dir("hair_bad");
    const auto path = dir.file("bad.hair");
    const auto good = encode_hair(test::grid_model(3, 4), 2u | 1u | 4u, 0);
    auto expect_error = [&](const std::vector<unsigned char>& bytes, const std::string& reason) {
        test::write_bytes(path, bytes);
        try {
            read_hair(path);
            FAIL("no error for: " << reason);
        } catch (const io_error& e) {
            CHECK(e.file() == path);
            CHECK_THAT(e.reason(), Catch::Contains(reason));
        }
    };
    SECTION("truncated anywhere") {
        for (std::size_t cut : {std::size_t(0), std::size_t(60), std::size_t(128), std::size_t(131), good.size() - 1})
            expect_error({good.begin(), good.begin() + std::ptrdiff_t(cut)}, "truncated");
    }
    SECTION("bad magic") {
        auto b = good;
        b[0] = 'X';
        expect_error(b, "magic");
    }
    SECTION("counts the file cannot hold are refused before allocating") {
        auto b = good;
        const std::uint32_t huge = 0xFFFFFFF0u;
        std::memcpy(b.data() + 4, &huge, 4); // strands
        expect_error(b, "strands cannot share 12 points");
        b = good;
        std::memcpy(b.data() + 8, &huge, 4); // points
        expect_error(b, "truncated: points array needs 4294967280 x 12 bytes");
    }
    SECTION("more strands than points, without a segments array") {
        auto b = encode_hair(test::grid_model(3, 4), 2u, 3);
        const std::uint32_t huge = 0xFFFFFFFFu;
        std::memcpy(b.data() + 4, &huge, 4);
        expect_error(b, "strands cannot share");
    }
    SECTION("point count disagreeing with the segments") {
        auto b = good;
        const std::uint32_t points = 11;
        std::memcpy(b.data() + 8, &points, 4);
        expect_error(b, "the strands hold 12 points but the header says 11");
    }
    SECTION("zero strands") {
        auto b = good;
        const std::uint32_t zero = 0;
        std::memcpy(b.data() + 4, &zero, 4);
        expect_error(b, "no strands");
    }
    SECTION("a NaN coordinate") {
        auto b = good;
        const float nan = std::numeric_limits<float>::quiet_NaN();
        std::memcpy(b.data() + 128 + 6 + 12 * 2 + 4, &nan, 4);
        expect_error(b, "non-finite");
    }
    SECTION("no points array") {
        auto b = good;
        const std::uint32_t fields = 1;
        std::memcpy(b.data() + 12, &fields, 4);
        expect_error(b, "no points array");
    }
    SECTION("a missing file") {
        CHECK_THROWS_WITH(read_hair(dir.file("absent.hair")), Catch::Contains("absent.hair: no such file"));
    }
}
