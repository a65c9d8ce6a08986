// Animation: apng_writer's files decode, frame by frame, to the pixels written (each frame's data
// rewrapped as a plain PNG and decoded by stb_image); `hairshadow animate` writes the requested number
// of frames and a table whose exact row is zero.
#include "test_support.hpp"

#include <hairshadow/io/png.hpp>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

using namespace hairshadow;

namespace {

struct decoded_apng {
    int width = 0, height = 0;
    std::uint32_t announced = 0, frame_controls = 0;
    bool crc_ok = true, sequence_ok = true;
    bool order_ok = true;    ///< IHDR first, acTL before any image data, IEND last
    bool controls_ok = true; ///< every fcTL 26 bytes, the whole image at (0, 0), dispose and blend 0
    std::vector<std::pair<int, int>> delays; ///< each frame's delay_num, delay_den
    int palette_colours = 0;                 ///< 0: full colour
    std::vector<std::vector<std::uint8_t>> frames; ///< RGB, each frame's data decoded as a PNG of its own
};

void chunk(std::vector<std::uint8_t>& out, const char* type, const std::uint8_t* data, std::size_t length) {
    detail::put_u32(out, std::uint32_t(length));
    const std::size_t at = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + length);
    detail::put_u32(out, detail::png_crc(0, out.data() + at, 4 + length));
}

/// Walks the chunks of an APNG; each frame's image data (IDAT, or fdAT without its sequence number)
/// is wrapped as a PNG of its own and decoded by stb_image.
decoded_apng decode_apng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    decoded_apng d;
    REQUIRE(bytes.size() > 8);
    const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    REQUIRE(std::equal(signature, signature + 8, bytes.begin()));
    std::vector<std::uint8_t> ihdr, plte, data;
    std::uint32_t expected_sequence = 0;
    bool seen_actl = false, seen_data = false, seen_iend = false;
    std::size_t chunks = 0;
    const auto flush = [&] {
        if (data.empty()) return;
        std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
        chunk(png, "IHDR", ihdr.data(), ihdr.size());
        if (!plte.empty()) chunk(png, "PLTE", plte.data(), plte.size());
        chunk(png, "IDAT", data.data(), data.size());
        chunk(png, "IEND", nullptr, 0);
        int w = 0, h = 0, n = 0;
        unsigned char* pixels = stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &n, 3);
        REQUIRE(pixels != nullptr);
        d.frames.emplace_back(pixels, pixels + std::size_t(w) * std::size_t(h) * 3);
        stbi_image_free(pixels);
        data.clear();
    };
    for (std::size_t at = 8; at + 12 <= bytes.size();) {
        const std::uint32_t length = detail::get_u32(&bytes[at]);
        REQUIRE(at + 12 + length <= bytes.size());
        const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
        const std::uint8_t* body = &bytes[at + 8];
        d.crc_ok = d.crc_ok && detail::get_u32(body + length) == detail::png_crc(0, &bytes[at + 4], 4 + length);
        d.order_ok = d.order_ok && !seen_iend && (chunks++ == 0) == (type == "IHDR");
        seen_iend = seen_iend || type == "IEND";
        if (type == "IDAT" || type == "fdAT") d.order_ok = d.order_ok && seen_actl, seen_data = true;
        if (type == "acTL") d.order_ok = d.order_ok && !seen_data, seen_actl = true;
        if (type == "IHDR") {
            ihdr.assign(body, body + length);
            d.width = int(detail::get_u32(body));
            d.height = int(detail::get_u32(body + 4));
        } else if (type == "PLTE") {
            d.order_ok = d.order_ok && !seen_data;
            plte.assign(body, body + length);
            d.palette_colours = int(length / 3);
        } else if (type == "acTL") {
            d.announced = detail::get_u32(body);
        } else if (type == "fcTL") {
            flush();
            ++d.frame_controls;
            d.sequence_ok = d.sequence_ok && detail::get_u32(body) == expected_sequence++;
            d.controls_ok = d.controls_ok && length == 26 && int(detail::get_u32(body + 4)) == d.width && int(detail::get_u32(body + 8)) == d.height &&
                            detail::get_u32(body + 12) == 0 && detail::get_u32(body + 16) == 0 && body[24] == 0 && body[25] == 0;
            d.delays.push_back({body[20] << 8 | body[21], body[22] << 8 | body[23]});
        } else if (type == "IDAT") {
            data.insert(data.end(), body, body + length);
        } else if (type == "fdAT") {
            d.sequence_ok = d.sequence_ok && detail::get_u32(body) == expected_sequence++;
            data.insert(data.end(), body + 4, body + length);
        }
        at += 12 + length;
    }
    flush();
    d.order_ok = d.order_ok && seen_iend;
    return d;
}

} // namespace

TEST_CASE("an animated PNG decodes to the frames written", "[animate][io]") {
    test::temp_dir dir("apng");
    const int w = 37, h = 21, frames = 5;
    std::vector<std::vector<std::uint8_t>> written;
    {
        apng_writer apng(dir.file("a.png"), w, h, 3, frames, 2, 25); // 80 ms a frame
        for (int f = 0; f < frames; ++f) {
            std::vector<std::uint8_t> rgb(std::size_t(w * h * 3));
            for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::uint8_t((i * 7 + std::size_t(f) * 31 + i / 111) % 251);
            apng.add_frame(rgb);
            written.push_back(rgb);
        }
        CHECK_THROWS_AS(apng.add_frame(written[0]), argument_error); // one more than announced
        apng.finish();
    }
    const auto d = decode_apng(dir.file("a.png"));
    CHECK(d.width == w);
    CHECK(d.height == h);
    CHECK(d.announced == std::uint32_t(frames));
    CHECK(d.frame_controls == std::uint32_t(frames));
    CHECK(d.crc_ok);
    CHECK(d.sequence_ok);
    CHECK(d.order_ok);
    CHECK(d.controls_ok);
    CHECK(d.delays == std::vector<std::pair<int, int>>(frames, {2, 25}));
    REQUIRE(d.frames.size() == std::size_t(frames));
    for (int f = 0; f < frames; ++f) CHECK(d.frames[std::size_t(f)] == written[std::size_t(f)]);
    // A viewer without APNG shows the first frame.
    int fw = 0, fh = 0, n = 0;
    unsigned char* first = stbi_load(dir.file("a.png").c_str(), &fw, &fh, &n, 3);
    REQUIRE(first != nullptr);
    CHECK(std::equal(written[0].begin(), written[0].end(), first));
    stbi_image_free(first);

    CHECK(d.palette_colours == 0);

    CHECK_THROWS_AS(apng_writer(dir.file("b.png"), 0, 4, 3, 1, 1, 10), argument_error);
    CHECK_THROWS_AS(apng_writer(dir.file("b.png"), 4, 4, 4, 1, 1, 10, png_colours::palette), argument_error);
    CHECK_THROWS_AS(apng_writer(dir.file("b.png"), 4, 4, 3, 0, 1, 10), argument_error);
    apng_writer short_of_frames(dir.file("c.png"), 4, 4, 3, 2, 1, 10);
    CHECK_THROWS_AS(short_of_frames.add_frame(std::vector<std::uint8_t>(5)), argument_error);
    short_of_frames.add_frame(std::vector<std::uint8_t>(48, 9));
    CHECK_THROWS_AS(short_of_frames.finish(), io_error);
}

TEST_CASE("a palette APNG keeps up to 256 colours exactly and comes close with more", "[animate][io]") {
    test::temp_dir dir("apng_palette");
    const int w = 64, h = 48;
    const auto frame = [&](int f, int colours) {
        std::vector<std::uint8_t> rgb(std::size_t(w * h * 3));
        for (int i = 0; i < w * h; ++i) {
            const int c = (i * 7 + f) % colours; // a colour ramp of `colours` steps across the channels
            rgb[std::size_t(3 * i)] = std::uint8_t(c * 255 / (colours - 1));
            rgb[std::size_t(3 * i + 1)] = std::uint8_t(255 - c * 255 / (colours - 1));
            rgb[std::size_t(3 * i + 2)] = std::uint8_t((c * 37) % 256);
        }
        return rgb;
    };
    for (const int colours : {200, 3000}) {
        CAPTURE(colours);
        std::vector<std::vector<std::uint8_t>> written;
        apng_writer apng(dir.file("p.png"), w, h, 3, 3, 1, 10, png_colours::palette);
        for (int f = 0; f < 3; ++f) apng.add_frame(written.emplace_back(frame(f, colours)));
        apng.finish();
        const auto d = decode_apng(dir.file("p.png"));
        CHECK(d.crc_ok);
        CHECK(d.order_ok);
        CHECK(d.palette_colours == std::min(colours, 256));
        REQUIRE(d.frames.size() == 3);
        double error = 0;
        for (int f = 0; f < 3; ++f)
            for (std::size_t i = 0; i < written[0].size(); ++i) error += std::abs(int(d.frames[std::size_t(f)][i]) - int(written[std::size_t(f)][i]));
        error /= 3.0 * double(written[0].size());
        CAPTURE(error);
        if (colours <= 256) CHECK(error == 0.0); // every colour of the first frame, and the others use the same ones
        else CHECK(error < 6.0);                 // 3000 colours in 256: within a few levels
        if (colours > 256) CHECK(error > 0.0);
    }
}

TEST_CASE("animate writes the frames asked for and a table of each method's error and flicker", "[cli][animate]") {
    test::temp_dir dir("cli_animate");
    const auto r = test::run_cli("animate procedural:wavy:strands=300:segments=12 --frames 4 --fps 8 --res 96 --size 48 --supersample 1 "
                                 "--methods dom:3,occ:128:4 --motion both --out " + dir.file("anim"));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto d = decode_apng(dir.file("anim/animate.png"));
    CHECK(d.announced == 4);
    CHECK(d.frame_controls == 4);
    CHECK(d.crc_ok);
    CHECK(d.order_ok);
    CHECK(d.controls_ok);
    CHECK(d.delays == std::vector<std::pair<int, int>>(4, {1, 8})); // 8 fps
    REQUIRE(d.frames.size() == 4);
    CHECK(d.width == 3 * 48); // dom:3, occ:128:4 and the exact reference, side by side
    CHECK(d.frames[0] != d.frames[1]); // the hair and the light move
    CHECK(d.palette_colours > 16);     // one palette, by default
    const auto csv = test::read_text(dir.file("anim/animate.csv"));
    CHECK_THAT(csv, Catch::StartsWith("method,mean_error,flicker,rebuild_median_ms"));
    CHECK_THAT(csv, Catch::Contains("\ndsm,")); // the reference's own row: its times (its errors are against itself)
    // The approximations err, and their error changes from frame to frame.
    for (const char* method : {"\ndom:3,", "\nocc:128:4,"}) {
        const auto at = csv.find(method);
        REQUIRE(at != std::string::npos);
        std::istringstream row(csv.substr(at + std::strlen(method)));
        double mean = 0, flicker = 0;
        char comma = 0;
        row >> mean >> comma >> flicker;
        CAPTURE(method, mean, flicker);
        CHECK(mean > 0.001);
        CHECK(flicker > 0.0);
    }
    CHECK_THAT(test::read_text(dir.file("anim/animate.md")), Catch::Contains("| dom:3 | "));
}

TEST_CASE("animate hands its frames to ffmpeg, and a failing ffmpeg costs only the MP4", "[cli][animate]") {
    test::temp_dir dir("cli_animate_ffmpeg");
    std::filesystem::create_directories(dir.file("bin"));
    const auto fake = [&](const std::string& body) {
        { std::ofstream(dir.file("bin/ffmpeg")) << "#!/bin/sh\n" << body << "\n"; }
        std::filesystem::permissions(dir.file("bin/ffmpeg"), std::filesystem::perms::owner_all);
    };
    const std::string run = "animate procedural:straight:strands=100:segments=6 --frames 3 --res 32 --size 32 --supersample 1 --methods osm:4 --out ";
    // A stand-in that stores what it reads where the MP4 goes (the last word, after file:).
    fake("for last; do :; done; cat > \"${last#file:}\"");
    const std::string with_fake = "PATH=" + dir.file("bin") + ":$PATH " + std::string(HAIRSHADOW_CLI) + " " + run;
    const auto run_with_fake = [&](const std::string& out) {
        return std::system((with_fake + out + " > " + dir.file("log.txt") + " 2>&1").c_str());
    };
    REQUIRE(run_with_fake(dir.file("ok")) == 0);
    CHECK_THAT(test::read_text(dir.file("log.txt")), Catch::Contains("wrote") && Catch::Contains("animate.mp4"));
    // 3 frames of (2 panels x 32 wide) x (labels + 32 high) RGB pixels reached it.
    const auto raw = std::filesystem::file_size(dir.file("ok/animate.mp4"));
    CHECK(raw % (3 * 64 * 3) == 0);
    CHECK(raw >= 3 * 64 * 32 * 3);
    // One that fails at once: the run goes on, the animated PNG is whole, the MP4 is reported missing.
    fake("exit 1");
    REQUIRE(run_with_fake(dir.file("bad")) == 0);
    CHECK_THAT(test::read_text(dir.file("log.txt")), Catch::Contains("ffmpeg could not write animate.mp4"));
    CHECK(decode_apng(dir.file("bad/animate.png")).frames.size() == 3);
}

TEST_CASE("animate refuses bad options with a usage error", "[cli][animate][errors]") {
    for (const char* args : {"--frames 0", "--fps 0", "--motion spin", "--amplitude nan", "--amplitude 120", "--methods osm:17", "--light dir:1,2",
                             "--res 0", "--size 8", "--supersample 9"}) {
        CAPTURE(args);
        const auto r = test::run_cli(std::string("animate procedural:straight:strands=10:segments=4 ") + args + " --out /nonexistent/never");
        CHECK(r.status == 2);
        CHECK_THAT(r.err, Catch::StartsWith("error: "));
    }
    CHECK(test::run_cli("animate").status == 2);
    CHECK(test::run_cli("animate procedural:bald").status == 2);
}
