// Deep OpenEXR export and import (io/deep_exr.hpp): the written samples composite, by OpenEXR's own
// reader and the rules of "Interpreting OpenEXR Deep Pixels", to the maps' transmittance; read_deep_exr
// answers as the maps do; the command exports and compares against a file; bad files are typed errors.
#include "sheets.hpp"
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/deep_exr.hpp>

#include <ImfDeepScanLineInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

using namespace hairshadow;

namespace {

/// A texel's samples as OpenEXR's own reader gives them (Z, ZBack where there is one, A).
struct openexr_image {
    int res = 0;
    std::vector<std::vector<deep_sample>> texels;
    Imf::DeepImageState state = Imf::DIS_MESSY;
};

openexr_image read_with_openexr(const std::string& path) {
    Imf::DeepScanLineInputFile in(path.c_str());
    openexr_image img;
    img.res = in.header().dataWindow().max.x + 1;
    if (Imf::hasDeepImageState(in.header())) img.state = Imf::deepImageState(in.header());
    const std::size_t texels = std::size_t(img.res) * std::size_t(img.res);
    std::vector<unsigned> counts(texels);
    std::vector<float*> z(texels), zb(texels), a(texels);
    const bool back = in.header().channels().findChannel("ZBack") != nullptr;
    const std::size_t xs = sizeof(float*), ys = xs * std::size_t(img.res);
    Imf::DeepFrameBuffer fb; // set once: OpenEXR reads the pointers behind z, zb and a at readPixels
    fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, (char*)counts.data(), sizeof(unsigned), sizeof(unsigned) * std::size_t(img.res)));
    fb.insert("Z", Imf::DeepSlice(Imf::FLOAT, (char*)z.data(), xs, ys, sizeof(float)));
    fb.insert("A", Imf::DeepSlice(Imf::FLOAT, (char*)a.data(), xs, ys, sizeof(float)));
    if (back) fb.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, (char*)zb.data(), xs, ys, sizeof(float)));
    in.setFrameBuffer(fb);
    in.readPixelSampleCounts(0, img.res - 1);
    img.texels.resize(texels);
    std::vector<std::vector<float>> zs(texels), zbs(texels), as(texels);
    for (std::size_t t = 0; t < texels; ++t) {
        zs[t].resize(counts[t]), zbs[t].resize(counts[t]), as[t].resize(counts[t]);
        z[t] = zs[t].data(), zb[t] = zbs[t].data(), a[t] = as[t].data();
    }
    in.readPixels(0, img.res - 1);
    for (std::size_t t = 0; t < texels; ++t)
        for (unsigned i = 0; i < counts[t]; ++i) img.texels[t].push_back({zs[t][i], back ? zbs[t][i] : zs[t][i], as[t][i]});
    return img;
}

/// Front-to-back compositing of the alpha channel: a point sample in front of `depth` whole, a volume
/// sample by the fraction x of it in front, as 1 - (1 - A)^x.
double composite(const std::vector<deep_sample>& samples, float depth) {
    double t = 1.0;
    for (const auto& s : samples) {
        if (!(s.z < depth)) continue;
        const double x = s.z_back > depth ? (double(depth) - s.z) / (double(s.z_back) - s.z) : 1.0;
        t *= std::pow(1.0 - double(s.alpha), x);
    }
    return t;
}

/// Tidy: sorted by Z (then ZBack) and no two overlapping (OpenEXR's ImfDeepImageState.h).
bool tidy(const std::vector<deep_sample>& s) {
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
        const bool sorted = s[i].z < s[i + 1].z || (s[i].z == s[i + 1].z && s[i].z_back < s[i + 1].z_back);
        if (!sorted || s[i].z_back > s[i + 1].z) return false;
    }
    return true;
}

struct sintel_maps {
    hair_model model;
    light_space light;
    deep_shadow_map exact;
};
const sintel_maps& sintel(int res) {
    static const sintel_maps m = [res] {
        auto model = read_tfx(test::sintel_hair());
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), res);
        deep_shadow_map exact(rasterize(model, light), light);
        return sintel_maps{std::move(model), light, std::move(exact)};
    }();
    return m;
}

} // namespace

TEST_CASE("deep exr: the exact map's samples composite, by OpenEXR's reader, to its transmittance", "[deep_exr]") {
    test::temp_dir dir("deep_exr_exact");
    const auto sheets = test::make_sheets(3, 32);
    const deep_shadow_map sheet_map(rasterize(sheets.model, sheets.light), sheets.light);
    for (const deep_shadow_map* map : {&sheet_map, &sintel(96).exact}) {
        write_deep_exr(dir.file("map.exr"), *map);
        const auto img = read_with_openexr(dir.file("map.exr"));
        REQUIRE(img.res == map->resolution());
        CHECK(img.state == Imf::DIS_TIDY);
        double worst = 0.0;
        std::size_t probes = 0;
        for (int y = 0; y < img.res; ++y)
            for (int x = 0; x < img.res; ++x) {
                const auto& s = img.texels[std::size_t(y) * std::size_t(img.res) + std::size_t(x)];
                REQUIRE(tidy(s));
                for (float d : map->depths(x, y))
                    for (float depth : {d, std::nextafter(d, 2.0f)}) {
                        worst = std::max(worst, std::abs(composite(s, depth) - double(map->transmittance(x, y, depth))));
                        ++probes;
                    }
            }
        CAPTURE(probes);
        CHECK(probes > 1000);
        CHECK(worst <= 1e-6);
    }
}

namespace {
/// The running minimum over [0, depth] of a compressed texel's function clamped at 0: what its file
/// holds (detail::falling_envelope). A piecewise-linear function's minimum over [0, depth] lies at a
/// vertex in front of depth or at depth itself.
double falling_envelope_at(const compressed_deep_shadow_map& map, int x, int y, float depth) {
    double least = std::max(0.0, double(map.transmittance(x, y, depth)));
    for (const auto& v : map.vertices(x, y))
        if (v.depth < depth) least = std::min(least, std::max(0.0, double(v.transmittance)));
    return std::min(least, 1.0);
}
} // namespace

TEST_CASE("deep exr: a compressed map's point and volume samples composite to its falling envelope", "[deep_exr][compression]") {
    test::temp_dir dir("deep_exr_compressed");
    const auto& exact = sintel(96).exact;
    for (float tolerance : {0.005f, 0.05f}) {
        const compressed_deep_shadow_map map(exact, tolerance);
        write_deep_exr(dir.file("map.exr"), map);
        const auto img = read_with_openexr(dir.file("map.exr"));
        CHECK(img.state == Imf::DIS_TIDY);
        double worst = 0.0, worst_exact = 0.0;
        std::size_t rises = 0, probes = 0;
        for (int y = 0; y < img.res; ++y)
            for (int x = 0; x < img.res; ++x) {
                const auto& s = img.texels[std::size_t(y) * std::size_t(img.res) + std::size_t(x)];
                REQUIRE(tidy(s));
                for (const auto& sample : s) REQUIRE((sample.alpha >= 0.0f && sample.alpha <= 1.0f)); // OpenEXR's rule for alpha
                const auto v = map.vertices(x, y);
                for (std::size_t i = 0; i < v.size(); ++i) {
                    if (i > 0 && v[i].transmittance > v[i - 1].transmittance) ++rises;
                    // The vertices, and 15 depths inside each piece: inside the volume samples, not only at their ends.
                    const float next = i + 1 < v.size() ? v[i + 1].depth : v[i].depth + 0.01f;
                    for (int k = 0; k < 16; ++k) {
                        const float depth = v[i].depth + (next - v[i].depth) * float(k) / 16.0f;
                        worst = std::max(worst, std::abs(composite(s, depth) - falling_envelope_at(map, x, y, depth)));
                        ++probes;
                    }
                }
                for (float d : exact.depths(x, y)) worst_exact = std::max(worst_exact, std::abs(composite(s, d) - double(exact.transmittance(x, y, d))));
            }
        CAPTURE(tolerance, probes, rises);
        CHECK(rises > 0); // the compressed functions do rise here and there: the envelope is tested where it differs
        CHECK(worst <= tolerance / 16.0 + 2e-6);              // the volume samples' budget (write_deep_exr), and float rounding
        CHECK(worst_exact <= tolerance * (1.0 + 1.0 / 16.0) + 2e-6); // and so within the map's tolerance of the exact map
    }
}

TEST_CASE("deep exr: a volume sample's exponential stays within the bound of the line it stands for, in few pieces", "[deep_exr]") {
    random_stream rng(3);
    std::vector<double> cuts;
    for (int i = 0; i < 2000; ++i) {
        const double x = rng.uniform(), y = i % 4 == 0 ? 0.0 : rng.uniform(), budget = 1e-5 + 0.01 * rng.uniform();
        const double p = std::max(x, y), q = std::min(x, y); // falling, to 0 a quarter of the time
        detail::volume_cuts(p, q, budget, cuts);
        REQUIRE(cuts.back() == q);
        double gap = 0.0, a = p;
        for (const double b : cuts) {
            REQUIRE(b <= a);
            for (int j = 1; j < 16; ++j) {
                const double f = j / 16.0, exponential = b > 0 && a > 0 ? a * std::pow(b / a, f) : 0.0;
                const double own = std::abs(a + f * (b - a) - exponential);
                CHECK(own <= detail::volume_gap_bound(a, b) * (1 + 1e-9) + 1e-15);
                gap = std::max(gap, own);
            }
            a = b;
        }
        CHECK(gap <= budget * (1 + 1e-9));
        CAPTURE(p, q, budget);
        CHECK(double(cuts.size()) <= 1.01 * std::sqrt(p / (2.0 * budget)) + 4.0); // geometric cuts; equal ones needed (p - q) / budget
    }
    detail::volume_cuts(0.5, 0.0, 0.01 / 16.0, cuts); // a slope down to T = 0 at tolerance 0.01: 800 equal cuts
    CHECK(cuts.size() <= 24);
    detail::volume_cuts(1.0, 0.0, 0.0, cuts); // no budget: held to 2^-24, still a bounded count
    CHECK(cuts.size() <= 3000);
}

TEST_CASE("deep exr: read back, the file answers as the maps do, and keeps the light bit for bit", "[deep_exr]") {
    test::temp_dir dir("deep_exr_round_trip");
    const auto& s = sintel(96);
    write_deep_exr(dir.file("exact.exr"), s.exact);
    const auto back = read_deep_exr(dir.file("exact.exr"));
    CHECK(back.light().parts() == s.light.parts());
    CHECK(back.method() == "dsm");
    CHECK_FALSE(back.tolerance());
    std::vector<float> want(s.model.point_count()), got(s.model.point_count());
    for (const query_options q : {query_options{}, query_options{true, false, 0.0f}, query_options{false, true, 0.001f}}) {
        s.exact.transmittance(s.model.points, want, q);
        back.transmittance(s.model.points, got, q);
        float worst = 0.0f;
        for (std::size_t i = 0; i < want.size(); ++i) worst = std::max(worst, std::abs(want[i] - got[i]));
        CHECK(worst <= 1e-6f);
    }
    float worst_texel = 0.0f; // at every fragment's depth (strictly in front: not counted) and just behind it
    for (int y = 0; y < s.exact.resolution(); ++y)
        for (int x = 0; x < s.exact.resolution(); ++x)
            for (float d : s.exact.depths(x, y))
                for (float depth : {d, std::nextafter(d, 2.0f)}) {
                    worst_texel = std::max(worst_texel, std::abs(back.transmittance(x, y, depth) - s.exact.transmittance(x, y, depth)));
                    REQUIRE(back.optical_depth(x, y, depth) == Approx(s.exact.optical_depth(x, y, depth)).epsilon(1e-5).margin(1e-6));
                }
    CHECK(worst_texel <= 1e-6f);
    const compressed_deep_shadow_map c(s.exact, 0.01f);
    write_deep_exr(dir.file("compressed.exr"), c);
    const auto cback = read_deep_exr(dir.file("compressed.exr"));
    CHECK(cback.method() == "dsm:0.01");
    CHECK(cback.tolerance() == 0.01f);
    // The file holds the compressed functions' falling envelope (alphas in [0, 1]), within the
    // tolerance and 1/16 of it of the exact map, at every model point.
    s.exact.transmittance(s.model.points, want);
    cback.transmittance(s.model.points, got);
    float worst = 0.0f;
    for (std::size_t i = 0; i < want.size(); ++i) worst = std::max(worst, std::abs(want[i] - got[i]));
    CHECK(worst <= 0.01f * (1.0f + 1.0f / 16.0f) + 2e-6f);
}

namespace {
/// Writes a deep image of OpenEXR's own making: `channels` (FLOAT) with every sample at `value`, one
/// sample a texel, and the hairshadow light where `with_light`.
void write_deep_by_hand(const std::string& path, int res, std::vector<std::string> channels, bool with_light, float value,
                        Imf::Compression compression = Imf::ZIPS_COMPRESSION, Imf::PixelType stored = Imf::FLOAT,
                        Imf::LineOrder order = Imf::INCREASING_Y) {
    Imf::Header h(res, res);
    h.setType(Imf::DEEPSCANLINE);
    h.compression() = compression;
    h.lineOrder() = order;
    for (const auto& c : channels) h.channels().insert(c, Imf::Channel(stored));
    if (with_light) detail::write_hairshadow_attributes(h, test::make_sheets(1, res).light, "dsm", std::nullopt);
    const std::size_t texels = std::size_t(res) * std::size_t(res);
    std::vector<unsigned> counts(texels, 1);
    const std::size_t size = stored == Imf::HALF ? sizeof(half) : sizeof(float);
    std::vector<char> values(texels * channels.size() * size);
    for (std::size_t i = 0; i < texels * channels.size(); ++i) {
        if (stored == Imf::HALF) *reinterpret_cast<half*>(&values[i * size]) = half(value);
        else *reinterpret_cast<float*>(&values[i * size]) = value;
    }
    std::vector<std::vector<char*>> pointers(channels.size(), std::vector<char*>(texels));
    Imf::DeepFrameBuffer fb;
    fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, (char*)counts.data(), sizeof(unsigned), sizeof(unsigned) * std::size_t(res)));
    for (std::size_t c = 0; c < channels.size(); ++c) {
        for (std::size_t t = 0; t < texels; ++t) pointers[c][t] = &values[(c * texels + t) * size];
        fb.insert(channels[c], Imf::DeepSlice(stored, (char*)pointers[c].data(), sizeof(char*), sizeof(char*) * std::size_t(res), size));
    }
    Imf::DeepScanLineOutputFile out(path.c_str(), h);
    out.setFrameBuffer(fb);
    out.writePixels(res);
}

/// The io_error read_deep_exr throws for `path`, or "" where it reads.
std::string read_error(const std::string& path) {
    try {
        (void)read_deep_exr(path);
    } catch (const io_error& e) {
        CHECK(e.file() == path);
        return e.reason();
    }
    return "";
}
} // namespace

TEST_CASE("deep exr: bad files are typed errors", "[deep_exr][hostile]") {
    test::temp_dir dir("deep_exr_bad");
    CHECK_THAT(read_error(dir.file("missing.exr")), Catch::Contains("no such file"));
    // Truncated at many lengths: each an io_error, never a crash.
    const auto sheets = test::make_sheets(2, 16);
    write_deep_exr(dir.file("good.exr"), deep_shadow_map(rasterize(sheets.model, sheets.light), sheets.light));
    const auto good = test::read_bytes(dir.file("good.exr"));
    CHECK(read_error(dir.file("good.exr")).empty());
    CHECK_THROWS_AS(write_deep_exr(dir.file("no/such/folder.exr"), deep_shadow_map(rasterize(sheets.model, sheets.light), sheets.light)), io_error);
    for (std::size_t cut : {std::size_t(0), std::size_t(3), std::size_t(40), good.size() / 4, good.size() / 2, good.size() - 20, good.size() - 1}) {
        CAPTURE(cut);
        test::write_bytes(dir.file("cut.exr"), {good.begin(), good.begin() + std::ptrdiff_t(cut)});
        CHECK_FALSE(read_error(dir.file("cut.exr")).empty());
    }
    { // a flat image
        Imf::Header h(4, 4);
        h.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        std::vector<float> z(16, 0.5f);
        Imf::FrameBuffer fb;
        fb.insert("Z", Imf::Slice(Imf::FLOAT, (char*)z.data(), sizeof(float), 4 * sizeof(float)));
        Imf::OutputFile out(dir.file("flat.exr").c_str(), h);
        out.setFrameBuffer(fb);
        out.writePixels(4);
    }
    CHECK_THAT(read_error(dir.file("flat.exr")), Catch::Contains("flat"));
    write_deep_by_hand(dir.file("no_a.exr"), 8, {"Z"}, true, 0.5f);
    CHECK_THAT(read_error(dir.file("no_a.exr")), Catch::Contains("no A channel"));
    write_deep_by_hand(dir.file("no_light.exr"), 8, {"Z", "A"}, false, 0.5f);
    CHECK_THAT(read_error(dir.file("no_light.exr")), Catch::Contains("hairshadow/resolution"));
    write_deep_by_hand(dir.file("nan.exr"), 8, {"Z", "A"}, true, std::nanf(""));
    CHECK_THAT(read_error(dir.file("nan.exr")), Catch::Contains("not finite"));
    write_deep_by_hand(dir.file("alpha.exr"), 8, {"Z", "A"}, true, 1.5f);
    CHECK_THAT(read_error(dir.file("alpha.exr")), Catch::Contains("outside [0, 1]"));
    write_deep_by_hand(dir.file("negative.exr"), 8, {"Z", "A"}, true, -0.5f);
    CHECK_THAT(read_error(dir.file("negative.exr")), Catch::Contains("outside [0, 1]"));
    write_deep_by_hand(dir.file("other.exr"), 8, {"Z", "A", "R"}, true, 0.25f); // another program's file, with the light
    CHECK(read_error(dir.file("other.exr")).empty());
    CHECK(read_deep_exr(dir.file("other.exr")).transmittance(1, 1, 0.5f) == Approx(0.75f)); // strictly in front only
    CHECK(read_deep_exr(dir.file("other.exr")).transmittance(1, 1, 0.26f) == Approx(0.75f));
    write_deep_by_hand(dir.file("half.exr"), 8, {"Z", "A"}, true, 0.25f, Imf::ZIPS_COMPRESSION, Imf::HALF); // HALF channels, which OpenEXR converts to the reader's FLOAT
    CHECK(read_deep_exr(dir.file("half.exr")).transmittance(1, 1, 0.5f) == Approx(0.75f));
}

TEST_CASE("deep exr: a file claiming more samples than its bytes hold is refused", "[deep_exr][hostile]") {
    test::temp_dir dir("deep_exr_huge");
    // Uncompressed, one scanline a chunk: each chunk holds its line's cumulative sample counts (1, 2).
    write_deep_by_hand(dir.file("small.exr"), 2, {"Z", "A"}, true, 0.5f, Imf::NO_COMPRESSION);
    auto bytes = test::read_bytes(dir.file("small.exr"));
    REQUIRE(read_error(dir.file("small.exr")).empty());
    const unsigned char table[8] = {1, 0, 0, 0, 2, 0, 0, 0};
    std::vector<std::size_t> tables;
    for (std::size_t i = 8; i + 8 <= bytes.size(); ++i)
        if (std::equal(table, table + 8, bytes.begin() + std::ptrdiff_t(i))) tables.push_back(i);
    REQUIRE(tables.size() == 2);
    const std::uint32_t huge = 0x0fffffffu; // 2^31 bytes of samples at most: OpenEXR 3.1 refuses more itself
    for (std::size_t i : tables) std::memcpy(&bytes[i], &huge, 4), std::memcpy(&bytes[i + 4], &huge, 4);
    test::write_bytes(dir.file("counts.exr"), bytes); // OpenEXR sees the counts disagree with the chunk's data size
    CHECK_FALSE(read_error(dir.file("counts.exr")).empty());
    // The chunk's unpacked size (the 8 bytes before its table) made to agree: OpenEXR would then
    // allocate them, so the reader's bound on a chunk's bytes refuses them first.
    const std::uint64_t unpacked = std::uint64_t(huge) * 8;
    for (std::size_t i : tables) std::memcpy(&bytes[i - 8], &unpacked, 8);
    test::write_bytes(dir.file("huge.exr"), bytes);
    CHECK_THAT(read_error(dir.file("huge.exr")), Catch::Contains("bytes unpacked from"));
}

TEST_CASE("deep exr: a chunk declaring more bytes than the file has is refused before OpenEXR allocates them", "[deep_exr][hostile]") {
    test::temp_dir dir("deep_exr_chunks");
    write_deep_by_hand(dir.file("small.exr"), 4, {"Z", "A"}, true, 0.5f, Imf::NO_COMPRESSION);
    const auto good = test::read_bytes(dir.file("small.exr"));
    REQUIRE(read_error(dir.file("small.exr")).empty());
    const std::string name = dir.file("small.exr"); // the walk keeps a reference to the name
    detail::exr_header_walk walk(good, name);
    walk.run();
    const std::size_t table = walk.end(); // four offsets, one a scanline
    std::uint64_t first = 0;
    std::memcpy(&first, &good[table], 8);
    REQUIRE(first == table + 32);
    const auto patched = [&](std::size_t at, std::uint64_t value) {
        auto bytes = good;
        std::memcpy(&bytes[at], &value, 8);
        test::write_bytes(dir.file("bad.exr"), bytes);
        return read_error(dir.file("bad.exr"));
    };
    // OpenEXR 3.1 would allocate the packed data size (2 GiB here) of a chunk with no samples before reading it.
    CHECK_THAT(patched(std::size_t(first) + 12, 0x7fffffffu), Catch::Contains("chunk 0 declares"));
    CHECK_THAT(patched(std::size_t(first) + 4, 0x7fffffffu), Catch::Contains("chunk 0 declares")); // the sample count table's size
    CHECK_THAT(patched(table + 8, good.size() + 100), Catch::Contains("chunk 1's offset points outside the file"));
    CHECK_THAT(patched(table + 24, 0), Catch::Contains("chunk 3's offset points outside the file")); // an incomplete file's table
    CHECK_THAT(patched(table, table), Catch::Contains("chunk 0's offset points outside the file")); // inside the table itself
    std::vector<unsigned char> cut(good.begin(), good.begin() + std::ptrdiff_t(table + 12)); // the table itself cut short
    test::write_bytes(dir.file("cut.exr"), cut);
    CHECK_FALSE(read_error(dir.file("cut.exr")).empty());
    { // OpenEXR seeks to the first chunk only and reads the others back to back: the table points at a
      // good copy of chunk 1 at the end, while the bytes after chunk 0, which OpenEXR reads as chunk 1,
      // declare 2 GiB of data.
        std::uint64_t second = 0, third = 0;
        std::memcpy(&second, &good[table + 8], 8), std::memcpy(&third, &good[table + 16], 8);
        auto bytes = good;
        bytes.insert(bytes.end(), good.begin() + std::ptrdiff_t(second), good.begin() + std::ptrdiff_t(third));
        const std::uint64_t copy = good.size(), none = 0, huge = 0x7fffffffu;
        std::memcpy(&bytes[table + 8], &copy, 8);
        std::memcpy(&bytes[std::size_t(second) + 4], &none, 8);
        std::memcpy(&bytes[std::size_t(second) + 12], &huge, 8);
        test::write_bytes(dir.file("moved.exr"), bytes);
        CHECK_THAT(read_error(dir.file("moved.exr")), Catch::Contains("chunk 1 does not start where the chunk read before it ends"));
    }
    { // An attribute that OpenEXR reads shorter than it declares (a floatvector of 6 bytes: one float
      // read, 2 bytes left, the first 0 ending OpenEXR's header early), so that OpenEXR would read
      // the offset table 2 bytes before the walk's end.
        auto bytes = good;
        const std::vector<unsigned char> attribute = {'j', 'u', 'n', 'k', 0, 'f', 'l', 'o', 'a', 't', 'v', 'e', 'c', 't', 'o', 'r', 0,
                                                      6, 0, 0, 0, 0, 0, 0x80, 0x3f, 0, 0};
        bytes.insert(bytes.begin() + std::ptrdiff_t(table - 1), attribute.begin(), attribute.end()); // before the header's last 0
        for (std::size_t i = 0; i < 4; ++i) { // the chunks moved by the attribute's bytes
            const std::size_t at = table + attribute.size() + 8 * i;
            std::uint64_t offset = 0;
            std::memcpy(&offset, &bytes[at], 8);
            offset += attribute.size();
            std::memcpy(&bytes[at], &offset, 8);
        }
        test::write_bytes(dir.file("short_attribute.exr"), bytes);
        CHECK_THAT(read_error(dir.file("short_attribute.exr")), Catch::Contains("does not read as the size it declares"));
    }
}

TEST_CASE("deep exr: files of every deep compression and line order OpenEXR 3.1 writes are read", "[deep_exr]") {
    test::temp_dir dir("deep_exr_orders");
    struct kind {
        Imf::Compression compression;
        Imf::LineOrder order;
        int res;
    };
    // OpenEXR 3.1 writes deep images only uncompressed, RLE or ZIPS (ZIP: "not valid for deep data"),
    // and scanline images in increasing or decreasing y (RANDOM_Y: "invalid line order").
    for (const kind k : {kind{Imf::RLE_COMPRESSION, Imf::INCREASING_Y, 8}, kind{Imf::RLE_COMPRESSION, Imf::DECREASING_Y, 9},
                         kind{Imf::NO_COMPRESSION, Imf::DECREASING_Y, 5}, kind{Imf::ZIPS_COMPRESSION, Imf::DECREASING_Y, 33}}) {
        CAPTURE(int(k.compression), int(k.order), k.res);
        write_deep_by_hand(dir.file("kind.exr"), k.res, {"Z", "A"}, true, 0.25f, k.compression, Imf::FLOAT, k.order);
        REQUIRE(read_error(dir.file("kind.exr")).empty());
        const auto map = read_deep_exr(dir.file("kind.exr"));
        CHECK(map.sample_count() == std::size_t(k.res) * std::size_t(k.res));
        CHECK(map.transmittance(k.res - 1, k.res - 1, 0.5f) == Approx(0.75f));
    }
}

TEST_CASE("deep exr: a write that fails part-way leaves no file", "[deep_exr][errors]") {
    test::temp_dir dir("deep_exr_failed_write");
    struct failing_map { // a map whose optical depth fails in its third row
        light_space ls = test::make_sheets(1, 8).light;
        const light_space& light() const { return ls; }
        float optical_depth(int, int y, float) const {
            if (y == 2) throw argument_error("no optical depth here");
            return 0.5f;
        }
    };
    CHECK_THROWS_AS(write_sampled_deep_exr(dir.file("partial.exr"), failing_map{}, 4), argument_error);
    CHECK_FALSE(std::filesystem::exists(dir.file("partial.exr")));
    std::filesystem::create_directories(dir.file("folder"));
    test::write_text(dir.file("folder/keep"), ""); // never removes what it did not make
    CHECK_THROWS_AS(write_sampled_deep_exr(dir.file("folder"), failing_map{}, 4), io_error);
    CHECK(std::filesystem::exists(dir.file("folder/keep")));
}

TEST_CASE("deep exr: export, then compare against the file, prints compare's table", "[deep_exr][cli]") {
    test::temp_dir dir("deep_exr_cli");
    const std::string common = test::sintel_hair() + " --light dir:0,-1,-1 --res 64";
    // The table without its build times, which differ from run to run.
    const auto errors = [](const std::string& out) {
        std::istringstream lines(out);
        std::string line, kept;
        while (std::getline(lines, line)) {
            if (!line.starts_with("| ") || line.starts_with("| method")) continue;
            std::vector<std::string> cells;
            std::istringstream cols(line);
            for (std::string cell; std::getline(cols, cell, '|');) cells.push_back(cell);
            cells.erase(cells.begin() + 4); // build (ms)
            for (const auto& c : cells) kept += c + "|";
            kept += "\n";
        }
        return kept;
    };
    for (const char* method : {"dsm", "dsm:0.01"}) {
        CAPTURE(method);
        const auto exported = test::run_cli("--threads 2 export " + common + " --method " + method + " --out " + dir.file("map.exr"));
        REQUIRE(exported.status == 0);
        const auto direct = test::run_cli("--threads 2 compare " + common + " --methods osm:16,dom:3");
        const auto from_file = test::run_cli("--threads 2 compare " + common + " --methods osm:16,dom:3 --reference " + dir.file("map.exr"));
        REQUIRE(direct.status == 0);
        REQUIRE(from_file.status == 0);
        if (std::string(method) == "dsm") CHECK(errors(from_file.out) == errors(direct.out));
        else CHECK_THAT(from_file.out, Catch::Contains("dsm:0.01"));
        CHECK_FALSE(errors(direct.out).empty());
    }
}
