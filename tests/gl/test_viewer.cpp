// The interactive viewer example under Xvfb: it opens its GL window, draws a fixed number of frames
// with the GL renderer and writes the last; the frame shows the hair (not just the background).
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include "../test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

TEST_CASE("the viewer draws frames in a window under Xvfb", "[gl][viewer]") {
    test::temp_dir dir("viewer");
    const std::string shot = dir.file("frame.png");
    const std::string command = "xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(HAIRSHADOW_VIEWER) +
                                " procedural:wavy:strands=800:segments=12 --frames 4 --screenshot " + shot + " > " + dir.file("log.txt") + " 2>&1";
    const int status = std::system(command.c_str());
    CAPTURE(command, test::read_text(dir.file("log.txt")));
    REQUIRE(status == 0);
    CHECK_THAT(test::read_text(dir.file("log.txt")), Catch::Contains("osm:16: 4 frames"));
    CHECK_THAT(test::read_text(dir.file("log.txt")), Catch::Contains("transparency none"));
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(shot.c_str(), &w, &h, &channels, 3);
    REQUIRE(pixels != nullptr);
    long not_background = 0, dark = 0;
    for (int i = 0; i < w * h; ++i) {
        const unsigned char* p = pixels + 3 * i;
        not_background += p[0] < 250 || p[1] < 250 || p[2] < 250;
        dark += p[0] < 128;
    }
    stbi_image_free(pixels);
    CHECK(w == 720);
    CHECK(not_background > w * h / 20); // the hair and its sphere cover a good part of the frame
    CHECK(dark > 100);                   // with shading and shadows, not a flat silhouette
}

TEST_CASE("the viewer draws transparent hair, and refuses an unknown mode", "[gl][viewer][transparency]") {
    test::temp_dir dir("viewer_transparency");
    const std::string viewer = "xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(HAIRSHADOW_VIEWER) + " procedural:wavy:strands=300:segments=8";
    for (const char* mode : {"occupancy", "exact"}) {
        const std::string command = viewer + " --transparency " + mode + " --frames 2 > " + dir.file("log.txt") + " 2>&1";
        const int status = std::system(command.c_str());
        CAPTURE(command, test::read_text(dir.file("log.txt")));
        REQUIRE(status == 0);
        CHECK_THAT(test::read_text(dir.file("log.txt")), Catch::Contains(std::string("transparency ") + mode));
    }
    const std::string bad = viewer + " --transparency sorted > " + dir.file("bad.txt") + " 2>&1";
    const int status = std::system(bad.c_str());
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 2);
    CHECK_THAT(test::read_text(dir.file("bad.txt")), Catch::Contains("unknown transparency"));
}

TEST_CASE("the viewer sways the hair and rebuilds its maps every frame", "[gl][viewer][motion]") {
    test::temp_dir dir("viewer_sway");
    const std::string still = dir.file("still.png"), swaying = dir.file("sway.png");
    const std::string viewer = "xvfb-run -a -s '-screen 0 1024x768x24' " + std::string(HAIRSHADOW_VIEWER) + " procedural:straight:strands=600:segments=8";
    for (const auto& [flags, shot] : {std::pair{std::string(""), still}, std::pair{std::string(" --sway"), swaying}}) {
        const std::string command = viewer + flags + " --frames 6 --screenshot " + shot + " > " + dir.file("log.txt") + " 2>&1";
        const int status = std::system(command.c_str());
        CAPTURE(command, test::read_text(dir.file("log.txt")));
        REQUIRE(status == 0);
        if (!flags.empty()) CHECK_THAT(test::read_text(dir.file("log.txt")), Catch::Contains("swaying"));
    }
    int w = 0, h = 0, n = 0, w2 = 0, h2 = 0;
    unsigned char* a = stbi_load(still.c_str(), &w, &h, &n, 3);
    unsigned char* b = stbi_load(swaying.c_str(), &w2, &h2, &n, 3);
    REQUIRE(a != nullptr);
    REQUIRE(b != nullptr);
    REQUIRE(w * h == w2 * h2);
    long moved = 0;
    for (int i = 0; i < 3 * w * h; ++i) moved += std::abs(int(a[i]) - int(b[i])) > 40;
    stbi_image_free(a);
    stbi_image_free(b);
    CHECK(moved > 200); // the hair is somewhere else
}
