// Hostile input: one regression test per defect that fuzzing and hostile command lines found
// (issue 17), and TressFX 3 files built from the published layout.

#include "test_support.hpp"

#include <hairshadow/core/map_queries.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/points_file.hpp>
#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <cstring>
#include <limits>

using namespace hairshadow;

namespace {
std::vector<unsigned char> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }
obj_contents obj(const std::string& text) { return parse_obj(bytes_of(text), "test.obj"); }

template <class T>
void put(std::vector<unsigned char>& bytes, std::size_t offset, T value) {
    if (bytes.size() < offset + sizeof(T)) bytes.resize(offset + sizeof(T));
    std::memcpy(bytes.data() + offset, &value, sizeof(T));
}
} // namespace

TEST_CASE(".data: a strand of no points copies nothing, first or later", "[io][data][hostile]") {
    // Defect 1: memcpy into the model's null point array (undefined behaviour; UBSan in CI sees it).
    std::vector<unsigned char> only_empty{1, 0, 0, 0, 0, 0, 0, 0};
    CHECK_THROWS_AS(parse_data(only_empty, "z.data"), io_error); // no segment at all
    std::vector<unsigned char> bytes;
    put(bytes, 0, std::int32_t(2));
    put(bytes, 4, std::int32_t(0));
    put(bytes, 8, std::int32_t(2));
    put(bytes, 12, glm::vec3(0, 0, 0));
    put(bytes, 24, glm::vec3(0, 1, 0));
    const auto m = parse_data(bytes, "first_empty.data");
    CHECK(m.strand_count() == 2);
    CHECK(m.strand_size(0) == 0);
    CHECK(m.point_count() == 2);
    CHECK(m.points[1] == glm::vec3(0, 1, 0));
}

TEST_CASE(".hair: a default colour that is not finite is refused", "[io][hair][hostile]") {
    auto model = test::grid_model(2, 3);
    model.default_color = glm::vec3(0, std::numeric_limits<float>::quiet_NaN(), 0);
    CHECK_THROWS_WITH(validate(model), Catch::Contains("default colour"));
    test::temp_dir dir("hostile_colour");
    write_hair(model, dir.file("nan.hair"));
    CHECK_THROWS_AS(read_hair(dir.file("nan.hair")), io_error);
}

TEST_CASE("lights that float cannot place are refused, and huge directions are scaled", "[light][hostile]") {
    const aabb box{glm::vec3(-0.1f), glm::vec3(0.1f)};
    // Defect 2: window coordinates at infinity from a spot light 1e34 away.
    CHECK_THROWS_AS(light_space::fit(parse_light_spec("spot:0,0,1e34:0,-1,0:20"), box, 64), argument_error);
    // Defect 3: a direction whose length overflows, and a point light 1e38 away.
    const auto huge = light_space::fit(parse_light_spec("dir:0,-2e19,-2e19"), box, 64);
    const auto unit = light_space::fit(parse_light_spec("dir:0,-1,-1"), box, 64);
    CHECK(huge.view_projection() == unit.view_projection());
    CHECK_THROWS_AS(light_space::fit(parse_light_spec("point:0,1e38,0"), box, 64), argument_error);
    CHECK_THROWS_WITH(light_space::fit(parse_light_spec("point:0,1e5,0"), box, 64), Catch::Contains("directional light"));
    CHECK_NOTHROW(light_space::fit(parse_light_spec("point:0,100,0"), box, 64)); // 1,000 radii: fine
    const auto tiny = light_space::fit(parse_light_spec("dir:1e-30,0,0"), box, 64); // tiny, but a direction
    CHECK(tiny.view_projection() == light_space::fit(parse_light_spec("dir:1,0,0"), box, 64).view_projection());
}

TEST_CASE("a model far from the origin for its size is refused, not silently unshadowed", "[light][hostile]") {
    // A model 1 mm across, 1e5 from the origin: float coordinates there step by 0.008.
    const aabb far_model{glm::vec3(1e5f, 0, 0), glm::vec3(1e5f + 1e-3f, 1e-3f, 1e-3f)};
    CHECK_THROWS_WITH(light_space::fit(light_spec::directional({0, -1, 0}), far_model, 64), Catch::Contains("from the origin"));
    const aabb near_model{glm::vec3(1.0f, 0, 0), glm::vec3(1.001f, 1e-3f, 1e-3f)};
    CHECK_NOTHROW(light_space::fit(light_spec::directional({0, -1, 0}), near_model, 64));
}

TEST_CASE("light specs wrong on their own fail to parse", "[light][hostile]") {
    for (const char* spec : {"dir:0,0,0", "spot:0,1,0:0,0,0:30", "spot:0,1,0:0,-1,0:89", "spot:0,1,0:0,-1,0:0"}) {
        INFO(spec);
        CHECK_THROWS_AS(parse_light_spec(spec), argument_error);
    }
}

TEST_CASE("a light far away but allowed still shadows the model", "[light][hostile]") {
    // Just inside the distance limit, a point light's maps must still resolve the model's depth: they
    // agree with those of a light ten times nearer (measured: 0.0026 mean difference against 0.27 mean
    // shadow), not the silent "every T = 1" of defects 2 and 3.
    const auto model = make_procedural({.style = hair_style::curly, .strands = 300, .segments = 12});
    const auto box = model.bounds();
    const float radius = 0.5f * box.diagonal();
    const raster_options options{.fixed_alpha = 0.3f};
    const auto build_at = [&](float radii) {
        auto map = make_shadow_map("dom:3");
        map->build(model, light_space::fit(light_spec::point(box.center() + glm::vec3(0, radii * radius, 0)), box, 128), options);
        return map;
    };
    const auto near_map = build_at(0.09f * max_light_distance_in_radii);
    const auto far_map = build_at(0.9f * max_light_distance_in_radii);
    double difference = 0.0, shadow = 0.0;
    for (const auto& p : model.points) {
        difference += std::abs(far_map->transmittance(p) - near_map->transmittance(p));
        shadow += 1.0 - near_map->transmittance(p);
    }
    difference /= double(model.point_count());
    shadow /= double(model.point_count());
    INFO("mean shadow " << shadow << ", mean |T_far - T_near| " << difference);
    CHECK(shadow > 0.1);
    CHECK(difference < 0.05 * shadow);
}

TEST_CASE("query bias must be finite and within the map's depth", "[query][hostile]") {
    // Defect 4.
    for (const float bias : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 1e30f, -2.0f})
        CHECK_THROWS_AS(query_options{.depth_bias = bias}.check(), argument_error);
    CHECK_NOTHROW(query_options{.depth_bias = 1.0f}.check());
    const auto model = test::grid_model(4, 4);
    auto map = make_shadow_map("dom:3");
    map->build(model, light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 32));
    std::vector<float> t(model.point_count());
    CHECK_THROWS_AS(map->transmittance(model.points, t, {.depth_bias = std::numeric_limits<float>::quiet_NaN()}), argument_error);
}

TEST_CASE("OBJ: materials are never opened", "[io][obj][hostile]") {
    // Defect 6a: `mtllib` followed to any path; /dev/zero read until memory ran out. From a file, so
    // that a reader that resolved material paths again would find these.
    test::temp_dir dir("hostile_mtllib");
    test::write_text(dir.file("a.obj"), "mtllib /dev/zero\nmtllib ../../../../../../../../dev/zero\nmtllib ../../proc/self/fd/0\n"
                                        "v 0 0 0\nv 0 1 0\nl 1 2\n");
    const auto contents = read_obj(dir.file("a.obj"));
    CHECK(contents.hair.strand_count() == 1);
}

TEST_CASE("OBJ: a large polygon is fanned in linear time", "[io][obj][hostile]") {
    // Defect 6b: ear clipping of a 40,000-vertex face took 25 s. The fan from the first vertex is
    // what the reader documents; the test checks its triangles, not a time.
    std::string text;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * 3.14159265358979 * i / n;
        char line[64]; // (appending formatted text: GCC 12 warns falsely on chained string +)
        std::snprintf(line, sizeof line, "v %.6f %.6f 0\n", std::cos(a), std::sin(a));
        text += line;
    }
    text += "f";
    for (int i = 1; i <= n; ++i) {
        text += ' ';
        text += std::to_string(i);
    }
    text += "\n";
    const auto contents = obj(text);
    REQUIRE(contents.mesh.triangles.size() == std::size_t(n - 2));
    for (std::size_t k = 0; k < contents.mesh.triangles.size(); ++k) {
        const auto& t = contents.mesh.triangles[k];
        CHECK((t[0] == 0 && t[1] == k + 1 && t[2] == k + 2));
    }
}

TEST_CASE("OBJ: every number is checked against its text", "[io][obj][hostile]") {
    // Defects 6c and 6d: undefined behaviour in tinyobjloader, and silent misreads with exit 0.
    CHECK_NOTHROW(obj("vw 0 1e38 1\nv 0 0 0\nv 0 1 0\nl 1 2\n")); // an unknown statement is skipped
    CHECK_THROWS_WITH(obj("v 0 0 1e2147483648\n"), Catch::Contains("line 1") && Catch::Contains("does not fit a float"));
    CHECK_THROWS_WITH(obj("v 0 0 0\nv nan 1 0\n"), Catch::Contains("line 2") && Catch::Contains("not finite"));
    CHECK_THROWS_WITH(obj("v 0 0 1e39\n"), Catch::Contains("does not fit a float"));
    CHECK_THROWS_WITH(obj("v 0 0 0\nv 0 1 0\nl 1 99999999999999999999\n"), Catch::Contains("line 3") && Catch::Contains("out of range"));
    CHECK_THROWS_WITH(obj("v 0 0 0\nv 0 1 0\nl 1 3\n"), Catch::Contains("vertex index 3 is out of range"));
    CHECK_THROWS_WITH(obj("v 0 0 0\nl 0 1\n"), Catch::Contains("vertex index 0"));
    CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nf 1 2\n"), Catch::Contains("three vertices"));
    CHECK_THROWS_WITH(obj("v 0 0\n"), Catch::Contains("three coordinates"));
    CHECK_THROWS_WITH(obj("v 0 0 x\n"), Catch::Contains("'x' is not a number"));
    CHECK_THROWS_WITH(obj("v 0 0 0\nl /1\n"), Catch::Contains("not a vertex index"));
    // Underflow reads as the nearest float, as strtof gives it; a leading '+' is a number's sign.
    const auto tiny = obj("v 1e-50 +2 -0\nv 0 1 0\nl 1 2\n");
    CHECK(tiny.hair.points[0] == glm::vec3(0, 2, 0));
    CHECK_THROWS_WITH(obj("v +-1 0 0\n"), Catch::Contains("is not a number"));
    // The forms that are fine: texture and normal indices, negative (relative) indices, comments, CRLF.
    const auto ok = obj("v 0 0 0 # a comment\r\nv 1 0 0\r\nv 1 1 0\r\nvt 0 0\nf 1/1 2/1/1 -1//1\nl -3 -2 -1\n");
    REQUIRE(ok.mesh.triangles.size() == 1);
    CHECK(ok.mesh.triangles[0] == std::array<std::uint32_t, 3>{0, 1, 2});
    REQUIRE(ok.hair.strand_count() == 1);
    CHECK(ok.hair.points[2] == glm::vec3(1, 1, 0));
}

TEST_CASE("OBJ: the Sintel head reads the same as before the reader changed", "[io][obj]") {
    const auto contents = read_obj(test::sintel_head());
    CHECK(contents.mesh.triangles.size() == 5952); // the file's 5,952 `f` lines, all triangles
    for (const auto& t : contents.mesh.triangles)
        for (const auto i : t) CHECK(i < contents.mesh.vertices.size());
}

TEST_CASE("TressFX: array offsets inside the header are refused", "[io][tfx][hostile]") {
    // Defect 7: header words read as points.
    test::temp_dir dir("hostile_tfx_offsets");
    write_tfx(test::grid_model(3, 4), dir.file("ok.tfx"), 4);
    auto bytes = test::read_bytes(dir.file("ok.tfx"));
    put(bytes, 12, std::uint32_t(16)); // the position offset, pointing into the header
    CHECK_THROWS_WITH(parse_tfx_file(bytes, "inside.tfx"), Catch::Contains("inside the 160-byte header"));
    put(bytes, 12, std::uint32_t(160));
    put(bytes, 24, std::uint32_t(8)); // the thickness offset
    CHECK_THROWS_WITH(parse_tfx_file(bytes, "inside.tfx"), Catch::Contains("thickness array offset 8"));
}

TEST_CASE("TressFX 3: the 296-byte layout reads, with its follow-hair count", "[io][tfx][hostile]") {
    // Built by hand from TressFX 3.1's TressFXFileObject, not by the library's writer.
    const std::uint32_t strands = 2, per_strand = 4;
    std::vector<unsigned char> bytes(296, 0);
    put(bytes, 0, 3.0f);
    put(bytes, 4, strands);
    put(bytes, 8, per_strand);
    put(bytes, 12, std::uint32_t(5)); // follow hairs per guide
    put(bytes, 16, std::int32_t(1));  // both ends immovable
    put(bytes, 144, std::uint32_t(296));                     // positions: float3, strand-major
    put(bytes, 148, std::uint32_t(296 + 12 * 8));            // per-strand thickness
    for (std::uint32_t i = 0; i < strands * per_strand; ++i) put(bytes, 296 + 12 * i, glm::vec3(float(i / per_strand), -float(i % per_strand), 0.5f));
    put(bytes, 296 + 96, 0.002f);
    put(bytes, 296 + 100, 0.003f);
    const auto contents = parse_tfx_file(bytes, "tressfx3.tfx");
    CHECK(contents.major_version == 3);
    CHECK(contents.follow_hairs_per_guide == 5);
    CHECK(contents.both_ends_immovable);
    const auto& m = contents.strands;
    CHECK(m.strand_count() == 2);
    CHECK(m.point_count() == 8);
    CHECK(m.points[5] == glm::vec3(1, -1, 0.5f));
    CHECK(m.thickness_at(3) == 0.002f);
    CHECK(m.thickness_at(4) == 0.003f);

    // The library's writer gives the same layout, and grows the follow hairs on request.
    test::temp_dir dir("hostile_tfx3");
    write_tfx(m, dir.file("written.tfx"), 3, 5);
    const auto again = parse_tfx_file(test::read_bytes(dir.file("written.tfx")), "written.tfx");
    CHECK(again.strands.points == m.points);
    CHECK(again.follow_hairs_per_guide == 5);
    const auto grown = grow_follow_hair(again.strands, again.follow_hairs_per_guide + 1, 0.01f);
    CHECK(grown.strand_count() == 12);

    auto truncated = bytes;
    truncated.resize(200);
    CHECK_THROWS_WITH(parse_tfx_file(truncated, "short.tfx"), Catch::Contains("TressFX 3 header"));
    auto too_long = bytes;
    put(too_long, 8, std::uint32_t(65));
    CHECK_THROWS_WITH(parse_tfx_file(too_long, "long.tfx"), Catch::Contains("4 to 64"));
    auto unknown = bytes;
    put(unknown, 0, 2.5f);
    CHECK_THROWS_WITH(parse_tfx_file(unknown, "old.tfx"), Catch::Contains("TressFX version 2.5"));
    put(unknown, 0, 5.0f);
    CHECK_THROWS_WITH(parse_tfx_file(unknown, "new.tfx"), Catch::Contains("TressFX version 5"));
}

TEST_CASE("the command prints a TressFX 3 file's strands, points and segments", "[cli][tfx][hostile]") {
    test::temp_dir dir("hostile_cli_tfx3");
    write_tfx(test::grid_model(6, 16), dir.file("groom.tfx"), 3, 3);
    const auto r = test::run_cli("info " + dir.file("groom.tfx"));
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("strands:  6") && Catch::Contains("points:   96") && Catch::Contains("segments: 90") &&
                          Catch::Contains("TressFX 3") && Catch::Contains("3 follow hairs per guide"));
}

TEST_CASE("procedural models: the size limit counts points, and every model validates", "[procedural][hostile]") {
    // Defect 8a: 2^27 strands of one segment made 2^28 points.
    CHECK_THROWS_WITH(make_procedural(parse_procedural_spec("procedural:straight:strands=134217728:segments=1")),
                      Catch::Contains("points exceeds"));
    // Defect 8b: a model with an infinite default thickness.
    for (const char* style : {"wavy", "curly"})
        CHECK_THROWS_WITH(make_procedural(parse_procedural_spec(std::string("procedural:") + style + ":strands=2:segments=2:amplitude=1e38:wavelength=1e-38")),
                          Catch::Contains("no usable model"));
    CHECK_THROWS_AS(grow_follow_hair(test::grid_model(2, 3), 2, 3e38f), argument_error);
    // Each strand looks through every clump: their number is capped.
    CHECK_THROWS_WITH(make_procedural(parse_procedural_spec("procedural:clumped:strands=16000000:segments=1:clumps=16000000")),
                      Catch::Contains("at most 4096"));
}

TEST_CASE("points files: every line holds three finite numbers", "[io][hostile]") {
    const auto p = parse_points(bytes_of("# x y z\n1 2 3\n\n -1e-3\t0 4e1\r\n"), "p.txt");
    REQUIRE(p.size() == 2);
    CHECK(p[1] == glm::vec3(-1e-3f, 0, 40));
    CHECK_THROWS_WITH(parse_points(bytes_of("1 2 3\n1 nan 3\n"), "p.txt"), Catch::Contains("line 2"));
    CHECK_THROWS_WITH(parse_points(bytes_of("1 2 1e39\n"), "p.txt"), Catch::Contains("line 1"));
    CHECK_THROWS_WITH(parse_points(bytes_of("1 2\n"), "p.txt"), Catch::Contains("three numbers"));
    CHECK_THROWS_WITH(parse_points(bytes_of("1 2 3 4\n"), "p.txt"), Catch::Contains("more than three"));
}

TEST_CASE("the command: a malformed or out-of-range option value exits 2 in every command", "[cli][hostile]") {
    // Defect 9: --res 0 exited 1 for query and memory but 2 for figure. Defects 4 and 5: NaN, infinite
    // and absurd values were accepted. The rule: a value wrong on its own is a usage error (2); an
    // error that depends on the input (a file, a light that does not fit the model) exits 1.
    test::temp_dir dir("hostile_cli_values");
    test::write_text(dir.file("p.txt"), "0 0 0\n");
    const std::string model = "procedural:straight:strands=20:segments=4";
    const std::vector<std::string> commands{"query " + model + " --points " + dir.file("p.txt"),
                                            "render " + model + " --view light --out " + dir.file("o.png"),
                                            "memory --method dom:3",
                                            "compare " + model + " --methods dom:3",
                                            "bench " + model + " --methods dom:3 --repeat 1",
                                            "figure --out " + dir.file("fig")};
    for (const auto& command : commands)
        for (const char* res : {"0", "16385", "-5", "x"}) {
            INFO(command << " --res " << res);
            CHECK(test::run_cli(command + " --res " + res).status == 2);
        }
    for (const char* bias : {"nan", "inf", "1e30", "-nan"}) {
        INFO("--bias " << bias);
        CHECK(test::run_cli("query " + model + " --points " + dir.file("p.txt") + " --bias " + bias).status == 2);
        CHECK(test::run_cli("compare " + model + " --methods dom:3 --bias " + bias).status == 2);
    }
    for (const char* backend : {"cpu", "gl"}) {
        INFO("--alpha nan --backend " << backend);
        CHECK(test::run_cli("query " + model + " --points " + dir.file("p.txt") + " --alpha nan --backend " + std::string(backend)).status == 2);
    }
    CHECK(test::run_cli("render " + model + " --azimuth inf --out " + dir.file("o.png")).status == 2);
    CHECK(test::run_cli("render " + model + " --azimuth 1e39 --out " + dir.file("o.png")).status == 2); // beyond a float
    CHECK(test::run_cli("query " + model + " --points " + dir.file("p.txt") + " --wide 1").status == 2);
    CHECK(test::run_cli("query " + model + " --points " + dir.file("p.txt") + " --light spot:0,1,0:0,-1,0:95").status == 2);
    CHECK(test::run_cli("figure --transparency nan --out " + dir.file("fig")).status == 2);
    // Input-dependent errors stay 1: a light too far for float depth.
    const auto far = test::run_cli("query " + model + " --points " + dir.file("p.txt") + " --light point:0,1e38,0");
    CHECK(far.status == 1);
    CHECK_THAT(far.err, Catch::StartsWith("error: "));
}
