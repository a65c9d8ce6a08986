// Any method exported as OpenEXR (issue 45): its stored maps as a flat tiled image (io/flat_exr.hpp),
// read back by OpenEXR's own tiled reader bit for bit; its optical depth sampled in depth as deep
// volume samples (write_sampled_deep_exr), which read_deep_exr answers as the method does at every
// sample depth; and `hairshadow export` writing both.
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/deep_exr.hpp>
#include <hairshadow/io/flat_exr.hpp>
#include <hairshadow/methods/registry.hpp>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfStringAttribute.h>
#include <ImfTiledInputFile.h>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <map>
#include <memory>

using namespace hairshadow;

namespace {

struct lit_sintel {
    hair_model model;
    light_space light;
};
const lit_sintel& lit_sintel_at(int res) {
    static std::map<int, lit_sintel> scenes;
    auto it = scenes.find(res);
    if (it == scenes.end()) {
        auto model = read_tfx(test::sintel_hair());
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), res);
        it = scenes.emplace(res, lit_sintel{std::move(model), light}).first;
    }
    return it->second;
}

std::unique_ptr<any_shadow_map> map_of(const std::string& spec, const lit_sintel& s) {
    auto map = make_shadow_map(spec);
    map->build(s.model, s.light);
    return map;
}

/// Every texel of every channel of a flat tiled file against the map's stored maps, bit for bit; the
/// header's tiles, channels and attributes.
void check_flat_file(const std::string& path, const any_shadow_map& map) {
    const int res = map.light().resolution(), maps = map.stored_maps();
    Imf::TiledInputFile in(path.c_str());
    const auto& h = in.header();
    REQUIRE(h.dataWindow().min == Imath::V2i(0, 0));
    REQUIRE(h.dataWindow().max == Imath::V2i(res - 1, res - 1));
    CHECK(in.tileXSize() == unsigned(std::min(res, 64)));
    CHECK(in.tileYSize() == unsigned(std::min(res, 64)));
    CHECK(in.levelMode() == Imf::ONE_LEVEL);
    int channels = 0;
    for (auto c = h.channels().begin(); c != h.channels().end(); ++c, ++channels) {
        CHECK(c.channel().type == Imf::FLOAT);
        CHECK(std::string(c.name()) == flat_exr_channel_name(channels, maps)); // alphabetical = k's order
    }
    REQUIRE(channels == maps);
    CHECK(detail::read_light_attributes(h, path).parts() == map.light().parts());
    CHECK(detail::optional_string(h, detail::exr_attribute::method) == map.spec().text);
    CHECK(h.findTypedAttribute<Imf::FloatAttribute>(detail::exr_attribute::tolerance) == nullptr);
    std::vector<std::vector<float>> values(std::size_t(maps), std::vector<float>(std::size_t(res) * std::size_t(res), -1.0f));
    Imf::FrameBuffer fb;
    for (int k = 0; k < maps; ++k)
        fb.insert(flat_exr_channel_name(k, maps), Imf::Slice(Imf::FLOAT, (char*)values[std::size_t(k)].data(), sizeof(float), sizeof(float) * std::size_t(res)));
    in.setFrameBuffer(fb);
    in.readTiles(0, in.numXTiles() - 1, 0, in.numYTiles() - 1);
    std::size_t differ = 0;
    for (int k = 0; k < maps; ++k)
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x)
                differ += std::bit_cast<std::uint32_t>(values[std::size_t(k)][std::size_t(y) * std::size_t(res) + std::size_t(x)]) !=
                          std::bit_cast<std::uint32_t>(map.stored_optical_depth(x, y, k));
    CHECK(differ == 0);
}

} // namespace

TEST_CASE("flat exr: channel names sort in map order", "[flat_exr]") {
    CHECK(flat_exr_channel_name(0, 4) == "map00.optical_depth");
    CHECK(flat_exr_channel_name(7, 16) == "map07.optical_depth");
    CHECK(flat_exr_channel_name(99, 100) == "map99.optical_depth");
    CHECK(flat_exr_channel_name(5, 128) == "map005.optical_depth");
    CHECK(flat_exr_channel_name(127, 128) == "map127.optical_depth");
}

TEST_CASE("flat exr: every stored map of every method, read by OpenEXR's tiled reader, is the map's bit for bit", "[flat_exr]") {
    test::temp_dir dir("flat_exr");
    int written = 0;
    for (const int res : {100, 24}) // 2 x 2 tiles of 64, the last ones partial; one tile of 24
        for (const auto& spec : example_specs()) {
            CAPTURE(res, spec);
            const auto map = map_of(spec, lit_sintel_at(res));
            if (map->stored_maps() == 0) {
                try {
                    write_flat_exr(dir.file("none.exr"), *map);
                    FAIL("a map without stored maps was written");
                } catch (const argument_error& e) {
                    CHECK_THAT(e.what(), Catch::Contains("deep"));
                }
                continue;
            }
            write_flat_exr(dir.file("maps.exr"), *map);
            check_flat_file(dir.file("maps.exr"), *map);
            ++written;
        }
    CHECK(written >= 10);
}

TEST_CASE("sampled deep exr: read back, the file answers exp(-omega) of the method at every sample depth", "[deep_exr]") {
    test::temp_dir dir("sampled_deep_exr");
    const auto& s = lit_sintel_at(48);
    constexpr int samples = 40;
    const auto depths = detail::uniform_sample_depths(samples);
    for (const auto& spec : example_specs()) {
        CAPTURE(spec);
        const auto map = map_of(spec, s);
        write_sampled_deep_exr(dir.file("map.exr"), *map, samples);
        const auto back = read_deep_exr(dir.file("map.exr"));
        CHECK(back.method() == spec);
        CHECK_FALSE(back.tolerance());
        CHECK(back.light().parts() == map->light().parts());
        // Monotone methods are reproduced as they are; one whose optical depth falls (occupancy's
        // estimates, series and moments ringing, a compressed function within its tolerance) as its
        // largest value so far. These families' optical depth never falls:
        const std::string family = parse_method_spec(spec).family;
        const bool monotone = family == "osm" || family == "dom" || family == "dc" || family == "rosm" || family == "ue" || family == "avsm" ||
                              family == "adsm" || spec == "dsm";
        double worst = 0.0, worst_between = 0.0;
        std::size_t falls = 0, shadowed = 0;
        for (int y = 0; y < s.light.resolution(); ++y)
            for (int x = 0; x < s.light.resolution(); ++x) {
                const auto samples_here = back.samples(x, y);
                for (std::size_t i = 0; i + 1 < samples_here.size(); ++i) // tidy: sorted, none overlapping
                    REQUIRE(samples_here[i].z_back <= samples_here[i + 1].z);
                double most = 0.0, before = 0.0;
                for (std::size_t i = 0; i < depths.size(); ++i) {
                    const double omega = map->optical_depth(x, y, depths[i]);
                    falls += omega < most;
                    most = std::max(most, omega);
                    if (i == 0 && most > 0.0) continue; // a point sample at 0 counts only behind it
                    worst = std::max(worst, std::abs(double(back.transmittance(x, y, depths[i])) - std::exp(-most)));
                    if (i > 0) { // half-way: optical depth linear between the sample depths (OpenEXR's volume rule)
                        const float mid = 0.5f * (depths[i - 1] + depths[i]);
                        worst_between = std::max(worst_between, std::abs(double(back.transmittance(x, y, mid)) - std::exp(-0.5 * (before + most))));
                    }
                    before = most;
                }
                shadowed += most > 0.0;
            }
        CAPTURE(falls, shadowed);
        CHECK(shadowed > 100);
        CHECK(worst <= 1e-6);
        CHECK(worst_between <= 1e-5);
        if (monotone) CHECK(falls == 0);
    }
    CHECK_THROWS_AS(write_sampled_deep_exr(dir.file("bad.exr"), *map_of("osm:16", s), 0), argument_error);
}

TEST_CASE("sampled deep exr: a texel's samples follow the running maximum and skip flat intervals", "[deep_exr]") {
    const std::vector<float> depths{0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
    const std::vector<double> omega{0.0, 0.0, 1.0, 0.5, 2.0}; // flat, rise, fall (kept at 1), rise
    std::vector<deep_sample> out;
    detail::sampled_texel_samples(depths, [&](float z) { return omega[std::size_t(z * 4.0f)]; }, out);
    REQUIRE(out.size() == 2);
    CHECK((out[0].z == 0.25f && out[0].z_back == 0.5f));
    CHECK(out[0].alpha == Approx(1.0 - std::exp(-1.0)).epsilon(1e-6));
    CHECK((out[1].z == 0.75f && out[1].z_back == 1.0f));
    CHECK(out[1].alpha == Approx(1.0 - std::exp(-1.0)).epsilon(1e-6)); // from the kept 1 to 2
}

TEST_CASE("export: any method as deep samples (compare reads it) or, with --flat, as its stored maps", "[deep_exr][flat_exr][cli]") {
    test::temp_dir dir("export_any_cli");
    const std::string common = test::sintel_hair() + " --light dir:0,-1,-1 --res 64";
    const auto deep = test::run_cli("--threads 2 export " + common + " --method osm:16 --samples 32 --out " + dir.file("osm.exr"));
    REQUIRE(deep.status == 0);
    CHECK(read_deep_exr(dir.file("osm.exr")).method() == "osm:16");
    const auto compared = test::run_cli("--threads 2 compare " + common + " --methods dom:3 --reference " + dir.file("osm.exr"));
    CHECK(compared.status == 0);
    CHECK_THAT(compared.out, Catch::Contains("dom:3"));
    const auto flat = test::run_cli("--threads 2 export " + common + " --method osm:16 --flat --out " + dir.file("flat.exr"));
    REQUIRE(flat.status == 0);
    Imf::TiledInputFile in(dir.file("flat.exr").c_str());
    int channels = 0;
    for (auto c = in.header().channels().begin(); c != in.header().channels().end(); ++c) ++channels;
    CHECK(channels == 16);
    const auto exact_flat = test::run_cli("export " + common + " --method dsm --flat --out " + dir.file("dsm.exr"));
    CHECK(exact_flat.status == 2);
    CHECK_THAT(exact_flat.err, Catch::Contains("without --flat"));
    CHECK(test::run_cli("export " + common + " --method osm:16 --samples 0 --out " + dir.file("bad.exr")).status == 2);
}
