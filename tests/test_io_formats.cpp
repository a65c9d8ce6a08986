#include "test_support.hpp"

#include <hairshadow/io/load.hpp>

#include <catch2/catch.hpp>

#include <cstring>

using namespace hairshadow;

TEST_CASE("the Sintel TressFX model reads with its published counts and bounds", "[io][tfx]") {
    const auto m = read_tfx(test::sintel_hair());
    CHECK(m.strand_count() == 11400);
    CHECK(m.point_count() == 182400);
    CHECK(m.segment_count() == 171000);
    const auto b = m.bounds();
    CHECK(b.min.x == Approx(-0.116).margin(5e-4));
    CHECK(b.max.x == Approx(0.103).margin(5e-4));
    CHECK(b.min.y == Approx(1.396).margin(5e-4));
    CHECK(b.max.y == Approx(1.675).margin(5e-4));
    CHECK(b.min.z == Approx(-0.130).margin(5e-4));
    CHECK(b.max.z == Approx(0.133).margin(5e-4));
    CHECK(m.default_thickness > 0.0f);
}

TEST_CASE("malformed .tfx files raise io_error", "[io][tfx][errors]") {
    test::temp_dir dir("tfx_bad");
    const auto path = dir.file("bad.tfx");
    auto sintel = test::read_bytes(test::sintel_hair());
    SECTION("truncated") {
        test::write_bytes(path, {sintel.begin(), sintel.begin() + 5000});
        CHECK_THROWS_WITH(read_tfx(path), Catch::Contains("bad.tfx: truncated"));
        test::write_bytes(path, {sintel.begin(), sintel.begin() + 10});
        CHECK_THROWS_WITH(read_tfx(path), Catch::Contains("truncated"));
    }
    SECTION("absurd strand count") {
        std::vector<unsigned char> b(sintel.begin(), sintel.begin() + 4096);
        const std::uint32_t huge = 0x7FFFFFFF;
        std::memcpy(b.data() + 4, &huge, 4);
        test::write_bytes(path, b);
        CHECK_THROWS_AS(read_tfx(path), io_error);
    }
    SECTION("zero strands") {
        const std::uint32_t zero = 0;
        std::memcpy(sintel.data() + 4, &zero, 4);
        test::write_bytes(path, sintel);
        CHECK_THROWS_WITH(read_tfx(path), Catch::Contains("no strands"));
    }
    SECTION("a NaN coordinate") {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        std::memcpy(sintel.data() + 160 + 16 * 100, &nan, 4);
        test::write_bytes(path, sintel);
        CHECK_THROWS_WITH(read_tfx(path), Catch::Contains("non-finite"));
    }
}

TEST_CASE("writing then reading .data is lossless", "[io][data]") {
    test::temp_dir dir("data_roundtrip");
    auto m = make_procedural({.style = hair_style::wavy, .strands = 40, .segments = 9, .seed = 7});
    m.add_strand(std::vector<glm::vec3>{{0.5f, 0.5f, 0.5f}}); // single-point strands occur in USC data
    const auto path = dir.file("m.data");
    write_data(m, path);
    const auto r = read_data(path);
    CHECK(r.points == m.points);
    CHECK(r.strand_offsets == m.strand_offsets);
    CHECK(load_model(path).points == m.points);
}

TEST_CASE("malformed .data files raise io_error", "[io][data][errors]") {
    test::temp_dir dir("data_bad");
    const auto path = dir.file("bad.data");
    auto check = [&](const std::vector<unsigned char>& bytes, const std::string& reason) {
        test::write_bytes(path, bytes);
        CHECK_THROWS_WITH(read_data(path), Catch::Contains(path) && Catch::Contains(reason));
    };
    std::vector<unsigned char> b;
    check(b, "truncated");
    test::append(b, std::int32_t(0));
    check(b, "at least 1");
    b.clear();
    test::append(b, std::int32_t(-5));
    check(b, "at least 1");
    b.clear();
    test::append(b, std::int32_t(2000000000)); // a count the file cannot hold
    test::append(b, std::int32_t(2));
    check(b, "truncated");
    b.clear();
    test::append(b, std::int32_t(1));
    test::append(b, std::int32_t(1000000000)); // points the file cannot hold
    check(b, "truncated");
    b.clear();
    test::append(b, std::int32_t(1));
    test::append(b, std::int32_t(2));
    test::append(b, glm::vec3(0, 0, 0));
    test::append(b, glm::vec3(1, 0, 0));
    test::append(b, std::int32_t(7));
    check(b, "trailing bytes");
    b.resize(b.size() - 4);
    test::write_bytes(path, b);
    CHECK(read_data(path).segment_count() == 1);
}

TEST_CASE("OBJ polylines become strands and faces an opaque mesh", "[io][obj]") {
    test::temp_dir dir("obj");
    const auto path = dir.file("m.obj");
    test::write_text(path, "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\n"
                           "l 1 2 3\nl 4 5\nf 1 2 4\nf 1 2 5 4\n");
    const auto contents = read_obj(path);
    REQUIRE(contents.hair.strand_count() == 2);
    CHECK(contents.hair.segment_count() == 3);
    CHECK(contents.hair.strand(0)[2] == glm::vec3(2, 0, 0));
    CHECK(contents.mesh.triangles.size() == 3); // the quad is split in two
    CHECK(load_model(path).strand_count() == 2);
}

TEST_CASE("the Sintel head mesh reads as triangles and holds no strands", "[io][obj]") {
    const auto contents = read_obj(test::sintel_head());
    CHECK(contents.mesh.vertices.size() == 3046);
    CHECK(contents.mesh.triangles.size() == 5952);
    CHECK_THROWS_WITH(read_obj_hair(test::sintel_head()), Catch::Contains("no polylines"));
}

TEST_CASE("malformed OBJ files raise io_error", "[io][obj][errors]") {
    test::temp_dir dir("obj_bad");
    const auto path = dir.file("bad.obj");
    test::write_text(path, "v 0 0 0\nv 1 0 0\nl 1 7\n");
    CHECK_THROWS_AS(read_obj(path), io_error);
    test::write_text(path, "v 0 0 0\nv nan 0 0\nl 1 2\n");
    CHECK_THROWS_AS(read_obj_hair(path), io_error);
    CHECK_THROWS_WITH(read_obj(dir.file("absent.obj")), Catch::Contains("no such file"));
}

TEST_CASE("load_model dispatches on the extension and rejects unknown ones", "[io]") {
    test::temp_dir dir("load");
    test::write_text(dir.file("m.xyz"), "nothing");
    CHECK_THROWS_WITH(load_model(dir.file("m.xyz")), Catch::Contains("unknown model format"));
    CHECK(load_model(test::sintel_hair()).strand_count() == 11400);
    CHECK(load_model("procedural:straight:strands=10:segments=4").segment_count() == 40);
}
