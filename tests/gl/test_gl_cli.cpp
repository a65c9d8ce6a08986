// The command's --backend gl: every method family built on GL (OSMesa and EGL's Mesa fallback here)
// answers queries as the CPU back end does; the exact reference and CPU-only options are refused.
#include "../sheets.hpp"
#include "../test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/data_format.hpp>

#include <catch2/catch.hpp>

#include <sstream>

using namespace hairshadow;

namespace {
std::vector<float> numbers(const std::string& text) {
    std::istringstream in(text);
    std::vector<float> out;
    for (float v; in >> v;) out.push_back(v);
    return out;
}
} // namespace

TEST_CASE("query --backend gl gives the CPU back end's transmittance", "[gl][cli]") {
    test::temp_dir dir("gl_cli_query");
    const auto scene = test::make_sheets(3, 64);
    write_data(scene.model, dir.file("sheets.data"));
    // Points in front of, between and behind the sheets, at several places across them.
    std::string points;
    for (float x : {-0.6f, -0.1f, 0.3f, 0.7f})
        for (float z : {0.9f, scene.sheet_z[0] - 0.05f, scene.sheet_z[1] - 0.05f, scene.sheet_z[2] - 0.05f, -0.9f})
            points += std::to_string(x) + " " + std::to_string(scene.row_y[scene.row_y.size() / 2 + 1]) + " " + std::to_string(z) + "\n";
    test::write_text(dir.file("points.txt"), points);
    const std::string common = "query " + dir.file("sheets.data") + " --light dir:0,0,-1 --res 64 --alpha 0.4 --points " + dir.file("points.txt");
    for (const char* method : {"osm:16", "osm:64:gamma", "dom:3", "dc:4", "occ:128:4", "docc:128:4", "rosm:16", "dom:3:8bit", "occ:128:4:8bit",
                               "adsm:0.5:0.1:0.3", "adsm:auto"}) {
        for (const char* context : {"osmesa", "egl"}) {
            CAPTURE(method, context);
            const auto cpu = test::run_cli(common + " --method " + method);
            const auto gl = test::run_cli(common + " --method " + method + " --backend gl --context " + context);
            REQUIRE(cpu.status == 0);
            REQUIRE(gl.status == 0);
            const auto a = numbers(cpu.out), b = numbers(gl.out);
            REQUIRE(a.size() == 20);
            REQUIRE(b.size() == a.size());
            for (std::size_t i = 0; i < a.size(); ++i) CHECK(b[i] == Approx(a[i]).margin(1e-4));
        }
        // The depth bias on GL, as the CPU query takes it: points just behind a sheet move in front of it.
        const auto cpu = test::run_cli(common + " --method " + method + " --bias 0.2");
        const auto gl = test::run_cli(common + " --method " + method + " --bias 0.2 --backend gl --context osmesa");
        const auto unbiased = test::run_cli(common + " --method " + method);
        REQUIRE(cpu.status == 0);
        REQUIRE(gl.status == 0);
        const auto a = numbers(cpu.out), b = numbers(gl.out), c = numbers(unbiased.out);
        REQUIRE(b.size() == a.size());
        for (std::size_t i = 0; i < a.size(); ++i) CHECK(b[i] == Approx(a[i]).margin(1e-4));
        CHECK(a != c);
    }
}

TEST_CASE("compare and render --backend gl", "[gl][cli]") {
    test::temp_dir dir("gl_cli_compare");
    const auto compare = test::run_cli("compare procedural:wavy:strands=300:segments=12 --res 128 --backend gl --context osmesa --methods "
                                       "osm:16,dc:4,occ:128:4 --out " + dir.file("out"));
    REQUIRE(compare.status == 0);
    CHECK_THAT(compare.out, Catch::Contains("Methods built on OpenGL"));
    for (const char* row : {"| osm:16 | 16 |", "| dc:4 | 4 |", "| occ:128:4 | 128 |"}) CHECK_THAT(compare.out, Catch::Contains(row));
    CHECK(std::filesystem::exists(dir.file("out/compare.csv")));
    const auto render = test::run_cli("render procedural:wavy:strands=300:segments=12 --view light --res 64 --backend gl --method dc:4 --out " +
                                      dir.file("t.png") + " --maps " + dir.file("maps"));
    REQUIRE(render.status == 0);
    CHECK(std::filesystem::file_size(dir.file("t.png")) > 0);
    CHECK(std::filesystem::exists(dir.file("maps/map_003.png")));
}

TEST_CASE("query --backend gl on either build path gives the CPU's transmittance", "[gl][cli][compute]") {
    test::temp_dir dir("gl_cli_path");
    const auto scene = test::make_sheets(3, 64);
    write_data(scene.model, dir.file("sheets.data"));
    std::string points;
    for (float x : {-0.6f, 0.3f})
        for (float z : {0.9f, scene.sheet_z[1] - 0.05f, -0.9f})
            points += std::to_string(x) + " " + std::to_string(scene.row_y[scene.row_y.size() / 2 + 1]) + " " + std::to_string(z) + "\n";
    test::write_text(dir.file("points.txt"), points);
    const std::string common = "query " + dir.file("sheets.data") + " --light dir:0,0,-1 --res 64 --alpha 0.4 --points " + dir.file("points.txt");
    for (const char* method : {"dom:3", "dc:4", "occ:128:4:8bit", "adsm:auto"}) {
        const auto cpu = test::run_cli(common + " --method " + method);
        REQUIRE(cpu.status == 0);
        for (const char* path : {"compute", "raster"}) {
            CAPTURE(method, path);
            const auto gl = test::run_cli(common + " --method " + method + " --backend gl --context osmesa --gl-path " + path);
            REQUIRE(gl.status == 0);
            const auto a = numbers(cpu.out), b = numbers(gl.out);
            REQUIRE(b.size() == a.size());
            for (std::size_t i = 0; i < a.size(); ++i) CHECK(b[i] == Approx(a[i]).margin(1e-4));
        }
    }
    for (const char* path : {"compute", "raster"}) {
        CAPTURE(path);
        const auto bench = test::run_cli("bench " + dir.file("sheets.data") + " --methods dom:3,occ:128:4 --res 64 --repeat 2 --backend gl --context osmesa --gl-path " +
                                         path);
        REQUIRE(bench.status == 0);
        CHECK_THAT(bench.out, Catch::Contains("GPU median (ms)") && Catch::Contains(std::string(path) + " build"));
    }
    for (const char* bad : {" --gl-path compute", " --backend gl --gl-path blend"}) {
        CAPTURE(bad);
        const auto r = test::run_cli(common + " --method dom:3" + bad);
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Catch::Contains("--gl-path"));
    }
}

TEST_CASE("the compute path needs no extension: with 64-bit integers hidden it gives the same answers", "[gl][cli][compute]") {
    // Mesa hides an extension when told to. Every method the compute path builds, density clustering's
    // k-means (the last to use 64-bit integers) among them, on the default path and on an explicit one.
    test::temp_dir dir("gl_cli_no_int64");
    std::string points; // 60 points through the model's box, most of them in its shadow
    for (const float x : {-0.2f, -0.1f, 0.0f, 0.1f, 0.2f})
        for (const float y : {-0.15f, -0.05f, 0.05f, 0.15f})
            for (const float z : {-0.2f, 0.0f, 0.2f}) points += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    test::write_text(dir.file("points.txt"), points);
    for (const char* method : {"dc:4", "dom:3", "occ:128:4", "msm"}) {
        CAPTURE(method);
        const std::string common = std::string("query procedural:curly:strands=400:segments=12 --backend gl --context osmesa --res 48 --method ") +
                                   method + " --points " + dir.file("points.txt");
        const auto with_extension = test::run_cli(common + " --gl-path compute");
        REQUIRE(with_extension.status == 0);
        std::istringstream answers(with_extension.out);
        int shadowed = 0;
        for (float t; answers >> t;) shadowed += t < 0.999f;
        CHECK(shadowed >= 20); // answers that a wrong map would change
        ::setenv("MESA_EXTENSION_OVERRIDE", "-GL_ARB_gpu_shader_int64", 1);
        const auto explicit_path = test::run_cli(common + " --gl-path compute");
        const auto default_path = test::run_cli(common);
        ::unsetenv("MESA_EXTENSION_OVERRIDE");
        CHECK(explicit_path.status == 0);
        CHECK(explicit_path.out == with_extension.out);
        CHECK(default_path.status == 0);
        CHECK(default_path.out == with_extension.out);
    }
}

TEST_CASE("the GL back end refuses what only the CPU does, with a usage error", "[gl][cli]") {
    const std::string model = "procedural:straight:strands=10:segments=4";
    struct refusal {
        const char* args;
        const char* message;
    };
    for (const auto& [args, message] : {refusal{" --method dsm", "CPU-only"}, refusal{" --method osm:16 --wide 4", "--wide"},
                                        refusal{" --method osm:16 --context glx", "--context"}}) {
        CAPTURE(args);
        const auto r = test::run_cli("render " + model + " --backend gl" + args);
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Catch::Contains(message));
    }
    // The CPU queries' filter and jitter (options of query and compare), refused by the GL back end
    // itself: the message is its own, not the option parser's.
    test::temp_dir dir("gl_cli_refusals");
    test::write_text(dir.file("points.txt"), "0 0 0\n");
    for (const char* option : {"--filter", "--jitter"}) {
        CAPTURE(option);
        const auto r = test::run_cli("query " + model + " --points " + dir.file("points.txt") + " --backend gl --method osm:16 " + option);
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Catch::Contains("the GLSL look-up has neither"));
    }
}

TEST_CASE("a context older than GL 4.3 is refused with the version it lacks", "[gl][cli][errors]") {
    // Mesa reports the version it is told to; the command asks for core 3.3 and each method checks.
    ::setenv("MESA_GL_VERSION_OVERRIDE", "3.3", 1);
    for (const char* context : {"osmesa", "egl"})
        for (const char* method : {"dom:3", "occ:128:4"}) {
            CAPTURE(context, method);
            const auto r = test::run_cli(std::string("render procedural:straight:strands=10:segments=4 --backend gl --context ") + context +
                                         " --method " + method + " --out " + (std::filesystem::temp_directory_path() / "old_gl.png").string());
            CHECK(r.status == 1);
            CHECK_THAT(r.err, Catch::Contains("needs OpenGL 4.3; the context has 3.3"));
        }
    ::unsetenv("MESA_GL_VERSION_OVERRIDE");
}

TEST_CASE("render draws the shaded scene on either back end, with fill lights", "[gl][cli][render]") {
    test::temp_dir dir("gl_cli_shaded");
    for (const char* backend : {"cpu", "gl"}) {
        CAPTURE(backend);
        const auto r = test::run_cli(std::string("render procedural:wavy:strands=400:segments=12 --res 128 --size 96 --method dom:3 ") +
                                     "--fill-light point:0.5,0.2,0.5 --backend " + backend + " --out " + dir.file(std::string(backend) + ".png"));
        REQUIRE(r.status == 0);
        CHECK_THAT(r.err, Catch::Contains("2 light(s)"));
        CHECK(std::filesystem::file_size(dir.file(std::string(backend) + ".png")) > 1000);
    }
    const auto maps = test::run_cli("render procedural:wavy:strands=40:segments=4 --maps " + dir.file("maps") + " --out " + dir.file("x.png"));
    CHECK(maps.status == 2);
    CHECK_THAT(maps.err, Catch::Contains("--view light"));
}

TEST_CASE("render blends transparent hair on GL, counting depth-peeling layers", "[gl][cli][transparency]") {
    test::temp_dir dir("gl_cli_transparency");
    for (const char* mode : {"occupancy", "weighted", "exact"}) {
        CAPTURE(mode);
        const auto r = test::run_cli(std::string("render procedural:wavy:strands=300:segments=10 --res 64 --size 64 --method occ:128:4 --backend gl ") +
                                     "--hair-opacity 0.3 --transparency " + mode + " --out " + dir.file(std::string(mode) + ".png"));
        REQUIRE(r.status == 0);
        CHECK_THAT(r.err, Catch::Contains(std::string("transparency ") + mode));
        CHECK(std::filesystem::file_size(dir.file(std::string(mode) + ".png")) > 100);
        if (std::string(mode) == "exact") {
            CHECK_THAT(r.err, Catch::Contains("depth peeling: "));
            CHECK_THAT(r.err, !Catch::Contains("depth peeling: 0 layers"));
        }
    }
}
