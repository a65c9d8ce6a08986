// The tiled build (methods/tiled_build.hpp): the maps of the fragment-buffer build, bit for bit, for
// every published method and hybrid, any thread count, tile size and line walk; its whole-map
// pre-pass; the line walk against the line rule; the persistent thread pool.
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <numeric>
#include <random>
#include <set>
#include <thread>
#include <tuple>

using namespace hairshadow;

namespace {

/// Sintel at 512x512, or a curly model of 3000 strands (a scaled-down copy of the 1.5M-segment
/// benchmark model, dense enough for 60 fragments per texel).
const hair_model& test_model(const std::string& name) {
    static const hair_model sintel = read_tfx(test::sintel_hair());
    static const hair_model curly = make_procedural({.style = hair_style::curly, .strands = 3000, .segments = 100, .seed = 1});
    return name == "sintel" ? sintel : curly;
}

/// Every texel of a and b equal, and the same whole-map extent.
template <class Method>
bool same_maps(const Method& a, const Method& b) {
    const int res = a.light().resolution();
    if (res != b.light().resolution()) return false;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x)
            if (!(a.texel(x, y) == b.texel(x, y))) {
                UNSCOPED_INFO("first difference at texel (" << x << ", " << y << ")");
                return false;
            }
    return true;
}

/// Whether the AVX-512 half of a test runs on this CPU; where it cannot (no AVX-512F, a build without
/// the vector paths, or HAIRSHADOW_NO_AVX512 set), says so: a visible skip, not a pass. The scalar
/// half of every such test runs everywhere (the suite runs them again with HAIRSHADOW_NO_AVX512 set).
bool avx512_half_runs() {
    if (detail::cpu_has_avx512()) return true;
    WARN("no AVX-512 here: the AVX-512 half of this test is skipped, its scalar half runs");
    return false;
}

struct build_config {
    unsigned threads;
    int tile;
    instruction_set instructions;
};

/// What a test changes in raster_options (std::optional members draw GCC's false maybe-uninitialized
/// warnings when copied at -O3).
struct raster_changes {
    float fixed_alpha = -1.0f; ///< none when negative
    float wide = 0.0f;
    bool depth_weighting = true;
};

/// The tiled build against the fragment-buffer build with the tiled build's own whole-map extent,
/// for several thread counts, tile sizes and both line walks.
template <class Method>
void check_tiled_equals_buffer(const hair_model& model, const light_space& light, raster_changes changes = {}) {
    raster_options base;
    if (changes.fixed_alpha >= 0.0f) base.fixed_alpha = changes.fixed_alpha;
    base.wide_line_width = changes.wide;
    base.depth_weighting = changes.depth_weighting;
    const std::vector<build_config> configs = {{1, 64, instruction_set::scalar}, {2, 64, instruction_set::automatic},
                                               {3, 16, instruction_set::automatic}, {8, 37, instruction_set::scalar},
                                               {2, 200, instruction_set::automatic}, {1, 8, instruction_set::automatic}};
    base.exec.threads = 1;
    const fragment_buffer fragments = rasterize(model, light, base);
    Method reference;
    for (const auto& c : configs) {
        CAPTURE(c.threads, c.tile, int(c.instructions));
        raster_options o = base;
        o.exec.threads = c.threads;
        o.tile_size = c.tile;
        o.instructions = c.instructions;
        Method tiled;
        tiled.build(model, light, o);
        reference.build(fragments, light, tiled.map_extent(), execution{1});
        CHECK(tiled.fragment_count() == fragments.size());
        CHECK(same_maps(tiled, reference));
    }
}

} // namespace

TEMPLATE_TEST_CASE("the tiled build gives the fragment-buffer build's maps, bit for bit", "[tiled][determinism]", opacity_shadow_maps<16>,
                   (opacity_shadow_maps<16, gamma_spacing>), deep_opacity_maps<3>, density_clustering<4>, (occupancy_maps<128, 4>),
                   deep_opacity_maps_8bit<3>, (deep_occupancy_maps<128, 4>), range_opacity_maps<16>,
                   (shadow_method<per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::ignore>, float_accumulation, interpolation>),
                   (opacity_shadow_maps<64, uniform_spacing, emulated_8bit>), (opacity_shadow_maps<37, gamma_spacing>),
                   (shadow_method<uniform_slices<64>, float_accumulation, occupancy_bitcount<2>>), (occupancy_maps<32, 1, emulated_8bit>),
                   (shadow_method<depth_range<24>, float_accumulation, interpolation>),
                   (shadow_method<per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation, interpolation>),
                   (density_clustering<3, emulated_8bit>)) {
    const std::string name = GENERATE("sintel", "curly");
    CAPTURE(name);
    const auto& model = test_model(name);
    const auto light = light_space::fit(light_spec::directional({0.3f, -1, -0.5f}), model.bounds(), name == "sintel" ? 512 : 256);
    check_tiled_equals_buffer<TestType>(model, light);
}

TEST_CASE("the tiled build gives the fragment-buffer build's maps on the 1.5M-segment curly model", "[tiled][dense]") {
    // The benchmark's model at 128x128: its 12.26 M fragments at 512x512 (98 a covered texel, at most
    // 292) become 3.06 M in 7,914 texels, 387 a texel and up to 1,025, past the 1,024 sums that
    // interpolation keeps per thread for a texel of one optical depth (accumulation/repeated_sums.hpp).
    const hair_model curly = make_procedural({.style = hair_style::curly, .strands = 10000, .segments = 150, .seed = 1});
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), curly.bounds(), 128);
    check_tiled_equals_buffer<deep_opacity_maps<3>>(curly, light);
    check_tiled_equals_buffer<occupancy_maps<128, 4>>(curly, light);
    check_tiled_equals_buffer<opacity_shadow_maps<16>>(curly, light);
    check_tiled_equals_buffer<density_clustering<4>>(curly, light);
}

TEST_CASE("the tiled build matches on the scalar paths: perspective lights, per-point attributes, fixed alpha, wide lines", "[tiled]") {
    const auto& sintel = test_model("sintel");
    SECTION("a point light (coverage weighted by depth)") {
        const auto light = light_space::fit(light_spec::point({0.4f, 2.2f, 0.6f}), sintel.bounds(), 256);
        check_tiled_equals_buffer<deep_opacity_maps<3>>(sintel, light);
        check_tiled_equals_buffer<occupancy_maps<128, 4>>(sintel, light);
    }
    SECTION("a spot light without depth weighting: one alpha, perspective interpolation") {
        const auto light = light_space::fit(light_spec::spot({0.0f, 2.2f, 0.0f}, {0, -1, 0}, 20.0f), sintel.bounds(), 256);
        check_tiled_equals_buffer<deep_opacity_maps<3>>(sintel, light, {.depth_weighting = false});
    }
    SECTION("per-point thickness and transparency") {
        hair_model m = make_procedural({.style = hair_style::wavy, .strands = 600, .segments = 24, .seed = 5});
        m.thickness.resize(m.point_count());
        m.transparency.resize(m.point_count());
        for (std::size_t i = 0; i < m.point_count(); ++i) {
            m.thickness[i] = 0.0004f + 0.0003f * float(i % 7);
            m.transparency[i] = 0.1f * float(i % 5);
        }
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), 200);
        check_tiled_equals_buffer<density_clustering<4>>(m, light);
        check_tiled_equals_buffer<opacity_shadow_maps<8>>(m, light);
    }
    SECTION("a fixed alpha and pre-filtered wide lines") {
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), sintel.bounds(), 256);
        check_tiled_equals_buffer<deep_opacity_maps<3>>(sintel, light, {.fixed_alpha = 0.3f});
        check_tiled_equals_buffer<occupancy_maps<128, 4>>(sintel, light, {.wide = 3.0f});
    }
}

TEST_CASE("maps that see part of the model, and segments clipped at the near plane, come out the same for every tile size", "[tiled]") {
    // A spot light inside the hair: segments behind it, crossing its near plane, and leaving its map.
    const auto& sintel = test_model("sintel");
    const auto centre = sintel.bounds().center();
    const auto light = light_space::fit(light_spec::spot(centre + glm::vec3(0.0f, 0.05f, 0.0f), {0.2f, -1.0f, 0.1f}, 35.0f), sintel.bounds(), 300);
    raster_options scalar;
    scalar.instructions = instruction_set::scalar;
    scalar.tile_size = 16;
    opacity_shadow_maps<16> reference;
    reference.build(sintel, light, scalar);
    CHECK(reference.fragment_count() > 10000);
    for (const int tile : {8, 24, 64, 128, 301}) {
        CAPTURE(tile);
        raster_options o;
        o.tile_size = tile;
        opacity_shadow_maps<16> osm;
        osm.build(sintel, light, o);
        CHECK(osm.map_extent().nearest == reference.map_extent().nearest);
        CHECK(osm.map_extent().furthest == reference.map_extent().furthest);
        CHECK(osm.fragment_count() == reference.fragment_count());
        CHECK(same_maps(osm, reference));
    }
    check_tiled_equals_buffer<occupancy_maps<128, 4>>(sintel, light);
}

TEST_CASE("the whole-map extent from the segments holds every fragment, and is close to the fragments' own", "[tiled][extent]") {
    const std::string name = GENERATE("sintel", "curly");
    CAPTURE(name);
    const auto& model = test_model(name);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 512);
    const fragment_buffer fragments = rasterize(model, light);
    const depth_extent exact = extent_of(fragments);
    deep_opacity_maps<3> dom;
    dom.build(model, light);
    const depth_extent from_segments = dom.map_extent();
    CHECK(from_segments.nearest <= exact.nearest);
    CHECK(from_segments.furthest >= exact.furthest);
    const float half_range_segments = 0.5f * (from_segments.furthest - from_segments.nearest), half_range_fragments = 0.5f * (exact.furthest - exact.nearest);
    WARN(name << ": DOM's default extent (half the depth range) " << half_range_segments << " from the segments, " << half_range_fragments
              << " from the fragments; nearest " << from_segments.nearest << " vs " << exact.nearest << ", furthest " << from_segments.furthest
              << " vs " << exact.furthest);
    CHECK(half_range_segments == Approx(half_range_fragments).epsilon(0.02));
    CHECK(dom.placement().extent() == Approx(std::max(half_range_segments, 1e-6f)));
    // OSM places its slices with the same extent.
    opacity_shadow_maps<16> osm;
    osm.build(model, light);
    CHECK(osm.placement().nearest() == from_segments.nearest);
    // An empty map: the same {0, 0} as an empty buffer.
    const auto elsewhere = light_space::fit(light_spec::directional({0, -1, -1}), aabb{glm::vec3(5.0f), glm::vec3(6.0f)}, 64);
    deep_opacity_maps<3> empty;
    empty.build(model, elsewhere);
    CHECK(empty.fragment_count() == 0);
    CHECK(empty.map_extent().nearest == 0.0f);
    CHECK(empty.map_extent().furthest == 0.0f);
}

TEST_CASE("a rebuild reuses its working memory and gives the same maps", "[tiled]") {
    const auto& model = test_model("sintel");
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 512);
    occupancy_maps<128, 4> occ;
    occ.build(model, light);
    const auto first = occ;
    const std::size_t workspace = occ.workspace_bytes();
    CHECK(workspace > 0);
    CHECK(first.workspace_bytes() == 0); // copies carry no working memory
    for (int i = 0; i < 3; ++i) occ.build(model, light);
    CHECK(occ.workspace_bytes() == workspace);
    CHECK(same_maps(occ, first));
    CHECK(count_fragments(model, light) == rasterize(model, light).size());
}

TEMPLATE_TEST_CASE("a map built again from another model, light or size writes every texel", "[tiled]",
                   deep_opacity_maps<3>, density_clustering<4>, (occupancy_maps<128, 4>)) {
    // A rebuild keeps the last build's texels, so every build must write each one, where it has
    // fragments and where not: texels left from Sintel seen from the side would show here.
    const auto& sintel = test_model("sintel");
    const auto& curly = test_model("curly");
    const auto side = light_space::fit(light_spec::directional({1, 0, 0}), sintel.bounds(), 256);
    const struct {
        const hair_model* model;
        light_space light;
    } builds[] = {{&sintel, side},
                  {&curly, light_space::fit(light_spec::directional({0.3f, -1, 0.2f}), curly.bounds(), 128)},  // smaller
                  {&curly, light_space::fit(light_spec::point({0.4f, 2.2f, 0.6f}), curly.bounds(), 320)},      // larger
                  {&sintel, light_space::fit(light_spec::directional({0, -1, -1}), sintel.bounds(), 256)}};
    TestType reused;
    for (const auto& b : builds) {
        CAPTURE(b.light.resolution());
        reused.build(*b.model, b.light);
        TestType fresh;
        fresh.build(*b.model, b.light);
        CHECK(same_maps(reused, fresh));
        // From a fragment buffer, the same.
        TestType from_fragments;
        from_fragments.build(sintel, side);
        from_fragments.build(rasterize(*b.model, b.light), b.light, fresh.map_extent());
        CHECK(same_maps(from_fragments, fresh));
    }
}

TEST_CASE("the tiled line walk keeps exactly the line rule's fragments", "[tiled][raster]") {
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::int64_t> near(-3 * subpixel_scale, 40 * subpixel_scale);
    std::uniform_int_distribution<std::int64_t> far(-(std::int64_t(1) << 27), std::int64_t(1) << 27);
    std::uniform_int_distribution<int> pick(0, 9);
    std::uniform_int_distribution<int> clip_corner(0, 24), clip_size(1, 20);
    auto coordinate = [&] {
        const int k = pick(rng);
        if (k == 0) return far(rng);
        if (k < 4) return near(rng) / subpixel_scale * subpixel_scale + (k == 1 ? 0 : subpixel_scale / 2); // texel corners and centres
        return near(rng);
    };
    int checked = 0;
    for (int i = 0; i < 40000; ++i) {
        const fixed_point a{coordinate(), coordinate()}, b{coordinate(), coordinate()};
        const int x0 = clip_corner(rng), y0 = clip_corner(rng);
        const texel_rect clip{x0, y0, x0 + clip_size(rng), y0 + clip_size(rng)};
        std::vector<std::pair<int, int>> expected, walked;
        rasterize_line(a, b, clip, [&](int x, int y) { expected.emplace_back(x, y); });
        walk_line(a, b, clip, [&](int x, int y, bool keep) {
            if (keep) walked.emplace_back(x, y);
        });
        if (expected != walked) {
            CAPTURE(a.x, a.y, b.x, b.y, clip.x0, clip.y0, clip.x1, clip.y1);
            CHECK(expected == walked);
            return;
        }
        // segment_bins' bound on a tile's fragments rests on this: at most one fragment per column of
        // an x-major line (row of a y-major one), within a texel of the segment's span.
        const bool x_major = std::abs(b.x - a.x) >= std::abs(b.y - a.y);
        const std::int64_t lo = x_major ? std::min(a.x, b.x) : std::min(a.y, b.y), hi = x_major ? std::max(a.x, b.x) : std::max(a.y, b.y);
        std::set<int> lines;
        for (const auto& [x, y] : expected) {
            const int line = x_major ? x : y;
            if (!lines.insert(line).second || line < (lo >> HAIRSHADOW_SUBPIXEL_BITS) - 1 || line > (hi >> HAIRSHADOW_SUBPIXEL_BITS) + 1) {
                CAPTURE(a.x, a.y, b.x, b.y, clip.x0, clip.y0, clip.x1, clip.y1, x, y);
                FAIL("two fragments in one line along the major axis, or one beyond the segment's span");
            }
        }
        checked += !expected.empty();
    }
    CHECK(checked > 5000);
}

TEST_CASE("no tile holds more fragments than segment_bins bounds it by, and the bound is near", "[tiled][raster]") {
    std::size_t tiles_checked = 0;
    for (const std::string name : {"sintel", "curly"})
        for (const int res : {256, 1024})
            for (const int tile : {8, 37, 64, 200})
                for (const bool point_light : {false, true}) {
                    CAPTURE(name, res, tile, point_light);
                    const auto& model = test_model(name);
                    const light_spec spec = point_light ? light_spec::point(model.bounds().center() + glm::vec3(0.0f, model.bounds().diagonal(), 0.0f))
                                                        : light_spec::directional({0.3f, -1.0f, 0.2f});
                    raster_options options;
                    options.tile_size = tile;
                    detail::segment_bins bins;
                    bins.prepare(model, light_space::fit(spec, model.bounds(), res), options);
                    detail::tile_fragments store;
                    std::size_t over = 0, largest = 0;
                    for (std::size_t t = 0; t < bins.tile_count(); ++t) {
                        store.gather(bins, t, instruction_set::automatic);
                        over += store.size() > bins.tile_fragment_bound(t);
                        largest = std::max(largest, store.size());
                    }
                    tiles_checked += bins.tile_count();
                    CHECK(over == 0);
                    CHECK(largest > 0);
                    CHECK(bins.largest_tile_fragment_bound() >= largest);
                    CHECK(bins.largest_tile_fragment_bound() <= 4 * largest + std::size_t(tile)); // not vacuous (short segments in small tiles: up to 3.3x)
                }
    CHECK(tiles_checked > 1000);
    // Wide lines have no such bound.
    raster_options wide;
    wide.wide_line_width = 2.0f;
    detail::segment_bins bins;
    bins.prepare(test_model("sintel"), light_space::fit(light_spec::directional({0, -1, 0}), test_model("sintel").bounds(), 128), wide);
    CHECK(bins.largest_tile_fragment_bound() == 0);
}

TEST_CASE("projection and binning list every segment in each tile it draws in; the AVX-512 code gives the scalar code's segments, tile lists, extent and bounds",
          "[tiled][raster][avx512]") {
    const bool vector_half = avx512_half_runs();
    // Strands of 1 to 40 points (the vector code's last batch of a strand is partial), segments
    // clipped at the near plane and leaving the map, an orthographic and two perspective lights, and
    // tiles from 8 texels (many segments of two or more tiles) to 256.
    hair_model ragged;
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-0.3f, 0.3f);
    for (std::size_t s = 0; s < 120; ++s) {
        const glm::vec3 root(u(rng), u(rng), u(rng));
        for (std::size_t i = 0; i < 1 + s % 40; ++i) ragged.points.push_back(root + glm::vec3(u(rng), u(rng), u(rng)) * (0.02f * float(i)));
        ragged.strand_offsets.push_back(std::uint32_t(ragged.points.size()));
    }
    const auto& sintel = test_model("sintel");
    const auto centre = sintel.bounds().center();
    struct scene {
        const hair_model* model;
        light_space light;
    };
    const scene scenes[] = {
        {&test_model("curly"), light_space::fit(light_spec::directional({0.3f, -1.0f, 0.2f}), test_model("curly").bounds(), 512)},
        {&sintel, light_space::fit(light_spec::directional({0, -1, -1}), sintel.bounds(), 300)},
        {&sintel, light_space::fit(light_spec::spot(centre + glm::vec3(0.0f, 0.05f, 0.0f), {0.2f, -1.0f, 0.1f}, 35.0f), sintel.bounds(), 256)},
        {&ragged, light_space::fit(light_spec::point({0.5f, 3.0f, 0.7f}), ragged.bounds(), 128)},
    };
    const auto bits = [](const auto& x) {
        std::array<unsigned char, sizeof(x)> b;
        std::memcpy(b.data(), &x, sizeof(x));
        return b;
    };
    // The scalar half: every segment's fragments, by the line rule over the whole map, fall in tiles
    // whose lists hold it, at depths within the whole-map extent.
    std::size_t segments_drawn = 0;
    for (const auto& [model, light] : scenes)
        for (const int tile : {8, 64}) {
            CAPTURE(model->strand_count(), light.resolution(), light.perspective(), tile);
            raster_options options;
            options.tile_size = tile;
            options.instructions = instruction_set::scalar;
            detail::segment_bins bins;
            bins.prepare(*model, light, options);
            const texel_rect map{0, 0, light.resolution(), light.resolution()};
            const int tiles_x = (light.resolution() + tile - 1) / tile;
            std::size_t unlisted = 0, outside_extent = 0;
            for (std::size_t i = 0; i < bins.segment_count(); ++i) {
                const auto shader = bins.shader(i);
                const detail::prepared_segment& seg = shader.segment();
                if (seg.empty()) continue;
                ++segments_drawn;
                std::size_t last_tile = std::size_t(-1);
                rasterize_line(seg.a(), seg.b(), map, [&](int x, int y) {
                    const float depth = shader.depth(shader.parameter(x, y));
                    outside_extent += !(depth >= bins.extent().nearest && depth <= bins.extent().furthest);
                    const std::size_t t = std::size_t(y / tile) * std::size_t(tiles_x) + std::size_t(x / tile);
                    if (t == last_tile) return;
                    last_tile = t;
                    const auto list = bins.tile_segments(t);
                    unlisted += !std::binary_search(list.begin(), list.end(), std::uint32_t(i)); // lists are in segment order
                });
            }
            CHECK(unlisted == 0);
            CHECK(outside_extent == 0);
        }
    CHECK(segments_drawn > 100000);
    if (!vector_half) return;
    for (const auto& [model, light] : scenes)
        for (const int tile : {8, 16, 64, 256})
            for (const bool bound_tiles : {true, false}) {
                CAPTURE(model->strand_count(), light.resolution(), light.perspective(), tile, bound_tiles);
                raster_options scalar_options, vector_options;
                scalar_options.tile_size = vector_options.tile_size = tile;
                scalar_options.instructions = instruction_set::scalar;
                vector_options.instructions = instruction_set::avx512;
                detail::segment_bins scalar, vector;
                scalar.prepare(*model, light, scalar_options, bound_tiles);
                vector.prepare(*model, light, vector_options, bound_tiles);
                REQUIRE(scalar.segment_count() == vector.segment_count());
                std::size_t differing = 0, drawn = 0;
                for (std::size_t i = 0; i < scalar.segment_count(); ++i) {
                    differing += bits(scalar.segment(i)) != bits(vector.segment(i));
                    drawn += !scalar.segment(i).empty();
                }
                CHECK(differing == 0);
                CHECK(drawn > 100);
                CHECK(bits(scalar.extent()) == bits(vector.extent()));
                REQUIRE(scalar.tile_count() == vector.tile_count());
                std::size_t lists_differing = 0, bounds_differing = 0;
                for (std::size_t t = 0; t < scalar.tile_count(); ++t) {
                    const auto a = scalar.tile_segments(t), b = vector.tile_segments(t);
                    lists_differing += !std::equal(a.begin(), a.end(), b.begin(), b.end());
                    bounds_differing += scalar.tile_fragment_bound(t) != vector.tile_fragment_bound(t);
                }
                CHECK(lists_differing == 0);
                CHECK(bounds_differing == 0);
                CHECK(scalar.tiles_by_load() == vector.tiles_by_load());
            }
}

#if HAIRSHADOW_AVX512_WALK
TEST_CASE("the AVX-512 walk's gathered batch set-up gives the lane-by-lane one, bounds and stand-ins included", "[tiled][raster][avx512]") {
    // Both set-ups are the vector walk's own: this test is all AVX-512 half.
    if (!avx512_half_runs()) return;
    // fill_batch serves models of 2^28 segments or more, too large to test by a build: it is checked
    // here against gather_batch, batch by batch. The spot light inside the hair leaves segments far
    // outside its map (beyond the walk's bounds: stand-ins) and has 1/w per segment.
    // Sintel with 64 strands from inside its box to points 200 box widths to the side: segments far
    // longer than the walk takes (stand-ins) under a light fitted to Sintel alone.
    hair_model sintel = test_model("sintel");
    const auto box = sintel.bounds();
    const auto centre = box.center();
    const float width = box.max.x - box.min.x;
    for (int i = 0; i < 64; ++i) {
        const float angle = 0.1f * float(i);
        sintel.points.push_back(centre + glm::vec3(0.001f * float(i), 0.0f, 0.0f));
        sintel.points.push_back(centre + 200.0f * width * glm::vec3(std::cos(angle), 0.0f, std::sin(angle)));
        sintel.strand_offsets.push_back(std::uint32_t(sintel.points.size()));
    }
    const light_space lights[] = {
        light_space::fit(light_spec::directional({0.0f, -1.0f, 0.0f}), box, 512),
        light_space::fit(light_spec::spot(centre + glm::vec3(0.0f, 0.05f, 0.0f), {0.2f, -1.0f, 0.1f}, 35.0f), box, 256),
    };
    const auto fields = [](const detail::avx512::batch& b) {
        std::array<unsigned char, 6 * 64 + 2> bytes;
        unsigned char* at = bytes.data();
        for (const void* field : {static_cast<const void*>(b.ax), static_cast<const void*>(b.ay), static_cast<const void*>(b.bx),
                                  static_cast<const void*>(b.by), static_cast<const void*>(b.depth_a), static_cast<const void*>(b.depth_delta)})
            std::memcpy(at, field, 64), at += 64;
        std::memcpy(at, &b.simd, 2);
        return bytes;
    };
    std::size_t batches = 0, differing = 0, stand_ins = 0, too_long = 0;
    for (const auto& light : lights)
        for (const int tile : {16, 64}) {
            raster_options o;
            o.tile_size = tile;
            o.depth_weighting = false;
            detail::segment_bins bins;
            bins.prepare(sintel, light, o);
            for (std::size_t t = 0; t < bins.tile_count(); ++t) {
                const auto list = bins.tile_segments(t);
                const texel_rect r = bins.tile_rect(t);
                const std::int64_t ox = std::int64_t(r.x0) << HAIRSHADOW_SUBPIXEL_BITS, oy = std::int64_t(r.y0) << HAIRSHADOW_SUBPIXEL_BITS;
                for (std::size_t base = 0; base < list.size(); base += 16) {
                    const int lanes = int(std::min<std::size_t>(16, list.size() - base));
                    detail::avx512::batch filled, gathered;
                    detail::avx512::fill_batch(filled, bins, list.data() + base, lanes, ox, oy);
                    detail::avx512::gather_batch(gathered, bins, list.data() + base, lanes, std::int32_t(ox), std::int32_t(oy));
                    ++batches;
                    differing += fields(filled) != fields(gathered);
                    stand_ins += std::size_t(lanes - std::popcount(unsigned(filled.simd)));
                    if (!light.perspective()) too_long += std::size_t(lanes - std::popcount(unsigned(filled.simd))); // 1/w is 1: the bounds
                }
            }
        }
    CHECK(batches > 1000);
    CHECK(differing == 0);
    CHECK(stand_ins > 0);
    CHECK(too_long > 0);
}
#endif

TEST_CASE("the scalar walk stores each texel's fragments as the fragment buffer holds them; the AVX-512 walk stores the scalar walk's, in its order, tile by tile",
          "[tiled][raster][avx512]") {
    const bool vector_half = avx512_half_runs();
    // Tiles of 8 to 200 texels: segments of at most sixteen texels in a tile are walked in lockstep,
    // longer ones alone (the coarse model's, up to a hundred texels and more), and a batch mixes both.
    const hair_model coarse = make_procedural({.style = hair_style::wavy, .strands = 400, .segments = 6, .seed = 3});
    const auto same = [](auto a, auto b) { return std::equal(a.begin(), a.end(), b.begin(), b.end()); };
    for (const hair_model* model : {&test_model("curly"), &coarse})
        for (const int res : {96, 512})
            for (const int tile : {8, 16, 37, 64, 200}) {
                CAPTURE(model->strand_count(), res, tile);
                raster_options options;
                options.tile_size = tile;
                const auto light = light_space::fit(light_spec::directional({0.3f, -1.0f, 0.2f}), model->bounds(), res);
                detail::segment_bins bins;
                bins.prepare(*model, light, options);
                // The scalar half: the fragment buffer's rasteriser (the line rule's own loop and shade())
                // against the walk (walk_line with its depth and optical depth), texel by texel.
                raster_options buffered = options;
                buffered.instructions = instruction_set::scalar;
                const fragment_buffer expected = rasterize(*model, light, buffered);
                detail::tile_fragments scalar, vector;
                std::size_t fragments = 0, differing = 0, texels_off = 0;
                for (std::size_t t = 0; t < bins.tile_count(); ++t) {
                    scalar.gather(bins, t, instruction_set::scalar);
                    fragments += scalar.size();
                    if (vector_half) {
                        vector.gather(bins, t, instruction_set::avx512);
                        differing += !(same(scalar.walk_texels(), vector.walk_texels()) && same(scalar.walk_depths(), vector.walk_depths()) &&
                                       same(scalar.walk_optical_depths(), vector.walk_optical_depths()));
                    }
                    scalar.group();
                    const texel_rect r = scalar.rect();
                    for (int y = r.y0; y < r.y1; ++y)
                        for (int x = r.x0; x < r.x1; ++x) {
                            const auto walked = scalar.texel(x, y);
                            const auto buffer = expected.texel(x, y);
                            bool same_texel = walked.size() == buffer.size();
                            for (std::size_t i = 0; same_texel && i < walked.size(); ++i)
                                same_texel = walked[i].depth == buffer[i].depth && walked[i].optical_depth == optical_depth_of(buffer[i].alpha);
                            texels_off += !same_texel;
                        }
                }
                CHECK(fragments == expected.size());
                CHECK(fragments > std::size_t(res));
                CHECK(texels_off == 0);
                CHECK(differing == 0);
            }
}

TEST_CASE("the walk in any order stores the segment-order walk's fragments, each texel's as a set, the same every time", "[tiled][raster][avx512]") {
    const bool vector_half = avx512_half_runs();
    // Long segments (the coarse model's) and short ones (curly's), tiles whose sides are no power of
    // two, and a perspective light that walks some segments apart.
    const hair_model coarse = make_procedural({.style = hair_style::wavy, .strands = 400, .segments = 6, .seed = 3});
    const auto ortho = light_spec::directional({0.3f, -1.0f, 0.2f});
    const auto spot = light_spec::point({0.4f, 2.2f, 0.6f});
    using fragment_tuple = std::tuple<std::uint32_t, float, float>;
    const auto fragments_of = [](const detail::tile_fragments& f) {
        std::vector<fragment_tuple> out;
        for (std::size_t i = 0; i < f.size(); ++i) out.emplace_back(f.walk_texels()[i], f.walk_depths()[i], f.walk_optical_depths()[i]);
        return out;
    };
    // Every tile size at 96x96; at 512x512 (the slow part under the sanitizers) the default tile and
    // one whose side is no power of two.
    const std::pair<int, int> sizes[] = {{96, 8}, {96, 16}, {96, 37}, {96, 64}, {96, 200}, {512, 37}, {512, 64}};
    for (const hair_model* model : {&test_model("curly"), &coarse})
        for (const light_spec* spec : {&ortho, &spot})
            for (const auto& [res, tile] : sizes) {
                CAPTURE(model->strand_count(), res, tile, spec == &spot);
                raster_options options;
                options.tile_size = tile;
                options.depth_weighting = false; // one alpha under the spot light too: the vector walk's tiles
                detail::segment_bins bins;
                bins.prepare(*model, light_space::fit(*spec, model->bounds(), res), options);
                detail::tile_fragments in_order, any, again;
                // The scalar half: without the vector walk, a walk in any order is the walk in segment
                // order, fragment for fragment.
                std::size_t fallback_off = 0;
                for (std::size_t t = 0; t < bins.tile_count(); ++t) {
                    in_order.gather(bins, t, instruction_set::scalar);
                    any.gather(bins, t, instruction_set::scalar, detail::fragment_order::any);
                    fallback_off += fragments_of(in_order) != fragments_of(any);
                }
                CHECK(fallback_off == 0);
                if (!vector_half) continue;
                std::vector<std::vector<fragment_tuple>> walked(bins.tile_count());
                std::size_t fragments = 0, reordered = 0, differing = 0, unstable = 0;
                for (std::size_t t = 0; t < bins.tile_count(); ++t) {
                    in_order.gather(bins, t, instruction_set::scalar);
                    any.gather(bins, t, instruction_set::avx512, detail::fragment_order::any);
                    auto expected = fragments_of(in_order), got = fragments_of(any);
                    walked[t] = got;
                    fragments += expected.size();
                    reordered += expected != got;
                    std::sort(expected.begin(), expected.end());
                    std::sort(got.begin(), got.end());
                    differing += expected != got;
                }
                // The order is the tile's own: walked again after other tiles (in reverse), as
                // another thread would, it is the same.
                for (std::size_t t = bins.tile_count(); t-- > 0;) {
                    again.gather(bins, t, instruction_set::avx512, detail::fragment_order::any);
                    unstable += fragments_of(again) != walked[t];
                }
                CHECK(fragments > std::size_t(res));
                CHECK(differing == 0);
                CHECK(unstable == 0);
                CHECK(reordered > 0); // the test walks the other order, not segment order again
            }
}

TEST_CASE("a build walks in any order only where its maps cannot tell: order-free policies, and no depth of -0", "[tiled]") {
    using dom = per_pixel_depth<3>;
    static_assert(detail::order_free_maps<dom, interpolation>);
    static_assert(detail::order_free_maps<depth_range<128>, occupancy_bitcount<4>>);
    static_assert(detail::order_free_maps<uniform_slices<16>, interpolation>);
    static_assert(detail::order_free_maps<clustered<4>, interpolation>); // k-means sums integers
    static_assert(!detail::order_free_maps<dom, fibre_density<fibre_density_source::measured>>); // says nothing
    CHECK(detail::walks_in_any_order<dom, interpolation>({0.1f, 0.9f}));
    CHECK(detail::walks_in_any_order<dom, interpolation>({-0.9f, -0.1f}));
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({0.0f, 0.9f}));   // an end at +0 may be -0 beside it
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({-0.2f, 0.9f}));  // ends of both signs: one may be -0
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({-0.9f, -0.0f}));
    CHECK_FALSE(detail::walks_in_any_order<dom, interpolation>({0.0f, 0.0f}));   // nothing reaches the map
    CHECK(detail::walks_in_any_order<clustered<4>, interpolation>({0.1f, 0.9f}));
    CHECK_FALSE(detail::walks_in_any_order<dom, fibre_density<fibre_density_source::measured>>({0.1f, 0.9f}));
}

TEST_CASE("the streamed depth pass gives add_to_depth_range's ranges, signed zeros and ties included, on both paths", "[tiled][placement]") {
    // Texels whose nearest or furthest depth is a zero met with both signs (which sign stays depends on
    // the comparisons' order and strictness), whose bounds tie, and random depths over many texels.
    // The ranges' bits must be the reference's.
    std::vector<std::uint32_t> texels;
    std::vector<float> depths;
    const std::vector<std::vector<float>> values = {{0.0f, -0.0f}, {0.0f, -0.0f, 0.5f, 0.5f}, {-0.0f, 0.0f, -0.5f, -2.0f}, {1.0f, 1.0f}};
    std::mt19937 random(11);
    for (std::uint32_t k = 0; k < 8; ++k)
        for (int i = 0; i < 40; ++i) texels.push_back(k), depths.push_back(values[k % 4][random() % values[k % 4].size()]);
    std::uniform_real_distribution<float> anywhere(-3.0f, 3.0f);
    for (int i = 0; i < 5000; ++i) texels.push_back(8 + std::uint32_t(random() % 200)), depths.push_back(anywhere(random));
    std::shuffle(texels.begin() + 320, texels.end(), random);
    constexpr float inf = std::numeric_limits<float>::infinity();
    std::vector<depth_extent> expected(208, depth_extent{inf, -inf});
    for (std::size_t i = 0; i < texels.size(); ++i) detail::add_to_depth_range(expected[texels[i]], depths[i]);
    for (const instruction_set path : {instruction_set::scalar, instruction_set::avx512}) {
        if (path == instruction_set::avx512 && !detail::cpu_has_avx512()) continue;
        std::vector<detail::negated_range> ranges(expected.size(), detail::negated_range{inf, inf});
        detail::add_depths(ranges.data(), texels.data(), depths.data(), texels.size(), path);
        std::size_t differing = 0;
        for (std::size_t k = 0; k < ranges.size(); ++k) {
            const float furthest = -ranges[k].neg_furthest;
            differing += std::memcmp(&ranges[k].nearest, &expected[k].nearest, sizeof(float)) != 0 ||
                         std::memcmp(&furthest, &expected[k].furthest, sizeof(float)) != 0;
            CHECK_FALSE(detail::empty_range(ranges[k]));
        }
        INFO("path " << int(path));
        CHECK(differing == 0);
    }
}

TEMPLATE_TEST_CASE("assign_each gives assign's layers, one at a time and sixteen at a time, at and beside every boundary", "[tiled][placement][avx512]",
                   per_pixel_depth<3>, (per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::ignore>),
                   (per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::extend>), per_pixel_depth<8>, uniform_slices<16>,
                   gamma_slices<16>, uniform_slices<5>, depth_range<128>, depth_range<24>, depth_range<1>, per_pixel_depth<16>,
                   (per_pixel_depth<128, layer_sizes::uniform, beyond_last_layer::extend>),
                   (per_pixel_depth<32, layer_sizes::linear, beyond_last_layer::ignore>)) {
    const bool vector_half = avx512_half_runs();
    using state = typename TestType::texel_state;
    TestType placement;
    placement.prepare(depth_extent{0.1f, 0.9f});
    // Texels with z0 (and, to extend, furthest) spread over the map's range.
    std::vector<state> states(37);
    for (std::size_t k = 0; k < states.size(); ++k)
        placement.texel_state_from(0.1f + 0.02f * float(k), 0.1f + 0.02f * float(k) + 0.013f * float(k % 11), states[k]);
    // Depths at each boundary of each texel, a few units in the last place either side, in front of the
    // first and beyond the last; a count that leaves a partial last step.
    std::vector<std::uint32_t> texels;
    std::vector<float> depths;
    for (std::uint32_t k = 0; k < states.size(); ++k)
        for (int b = 0; b <= TestType::layer_count; ++b) {
            float d = placement.boundary(states[k], b);
            for (int ulp = 0; ulp < 3; ++ulp) d = std::nextafter(d, -1.0f);
            for (int ulp = 0; ulp < 7; ++ulp, d = std::nextafter(d, 2.0f)) texels.push_back(k), depths.push_back(d);
            texels.push_back(k), depths.push_back(-1.0f);
            texels.push_back(k), depths.push_back(3.0f);
        }
    texels.push_back(5), depths.push_back(0.5f);
    REQUIRE(texels.size() % 16 != 0);
    std::vector<std::int32_t> scalar(texels.size(), -7), vector(texels.size(), -7);
    detail::assign_each(placement, std::span<const state>(states), texels, depths, std::span(scalar), instruction_set::scalar);
    if (vector_half) detail::assign_each(placement, std::span<const state>(states), texels, depths, std::span(vector), instruction_set::avx512);
    else vector = scalar;
    std::size_t differing = 0, wrong = 0;
    std::vector<bool> seen(std::size_t(TestType::layer_count) + 1);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        differing += scalar[i] != vector[i];
        wrong += scalar[i] != placement.assign(states[texels[i]], depths[i]);
        seen[std::size_t(scalar[i] + 1)] = true;
    }
    CHECK(differing == 0);
    CHECK(wrong == 0);
    CHECK(std::count(seen.begin(), seen.end(), true) >= TestType::layer_count); // every layer met
}

TEMPLATE_TEST_CASE("density clustering's per-texel steps: the scalar layers and counts are assign's; the vector pre-pass, bin assignment and bin counts give the scalar state, layers and counts, bit for bit",
                   "[tiled][placement][avx512]", clustered<1>, clustered<3>, clustered<4>, clustered<8>, clustered<16>) {
    const bool vector_half = avx512_half_runs();
    using state = typename TestType::texel_state;
    const TestType placement;
    random_stream random(7);
    // Texels of every count up to 70 (partial last steps; below clustered::vector_worthwhile, the
    // scalar steps), then ones made to meet each special case.
    std::vector<std::vector<optical_fragment>> texels;
    for (int n = 1; n <= 70; ++n) {
        std::vector<optical_fragment> t;
        for (int i = 0; i < n; ++i) t.push_back({random.uniform(0.2f, 0.8f), random.uniform(0.0f, 2.0f)});
        texels.push_back(t);
        // Repeated depths (ties between centres), few distinct values, and clusters that take nothing.
        for (auto& f : t) f.depth = 0.25f + 0.125f * float(int(f.depth * 8.0f) % 3);
        texels.push_back(t);
        // One optical depth throughout (a model of one alpha): the vector passes count the fragments
        // each cluster takes instead of adding their weights.
        for (auto& f : t) f = {random.uniform(0.2f, 0.8f), 0.7f};
        texels.push_back(t);
    }
    texels.push_back(std::vector<optical_fragment>(23, {0.5f, 0.3f}));                       // one depth: bins of no width
    texels.push_back({{0.0f, 0.1f}, {-0.0f, 0.2f}, {0.5f, 0.1f}, {-0.0f, 0.4f}});            // a zero of either sign at the front
    texels.push_back({{0.4f, 0.0f}, {0.6f, 0.0f}, {0.7f, 0.0f}, {0.3f, 0.0f}, {0.2f, 0.0f}}); // no weight: no cluster usable
    // Terms past the vector's exact range (2^15), in the second pass and in the first, but within the
    // scalar's (2^27).
    texels.push_back({{0.4f, 0.5f}, {1000.0f, 1.5f}, {0.7f, 0.25f}, {0.41f, 0.5f}, {0.9f, 1.0f}});
    texels.push_back(std::vector<optical_fragment>(5, {20000.0f, 2.0f}));
    texels.push_back({{0.4f, 0.5f}, {1000.0f, 0.5f}, {0.7f, 0.5f}, {0.41f, 0.5f}, {0.9f, 0.5f}}); // one b, past the range in the second pass
    texels.push_back({{0.4f, 0.0f}, {0.6f, -0.0f}, {0.7f, 0.0f}, {0.3f, -0.0f}, {0.2f, 0.0f}});  // b of zero, either sign: one b
    std::vector<optical_fragment> last_differs(40, {0.3f, 1.25f});
    for (std::size_t i = 0; i < last_differs.size(); ++i) last_differs[i].depth += 0.01f * float(i);
    last_differs.back().optical_depth = 1.5f; // one b but in the last, partial step
    texels.push_back(last_differs);
    std::vector<optical_fragment> spread;
    for (int i = 0; i < 200; ++i) spread.push_back({i % 2 ? -1.5f + 0.01f * float(i) : 1.9f - 0.005f * float(i), 6.5f});
    texels.push_back(spread); // the whole range of depths and the largest optical depth
    std::vector<optical_fragment> zeros(20, {0.5f, 1.0f});
    zeros[3].depth = 0.0f, zeros[17].depth = -0.0f; // in order +0 comes first; in lanes, -0 (lane 1)
    texels.push_back(zeros);
    constexpr std::size_t K = std::size_t(TestType::layer_count);
    std::size_t differing_states = 0, differing_layers = 0, differing_counts = 0, differing_ranges = 0, differing_one_b = 0, texels_of_one_b = 0,
                fragments = 0, differing_maps = 0, texels_alone = 0, layered = 0;
    for (const auto& t : texels) {
        const std::span<const optical_fragment> in(t);
        // The scalar half: the texel's range is its nearest and furthest depth, and the grouped build's
        // layers and counts, through their dispatch, are assign's.
        const depth_extent range = detail::depth_range_of(in);
        const auto [lo, hi] = std::minmax_element(t.begin(), t.end(), [](const auto& a, const auto& b) { return a.depth < b.depth; });
        differing_ranges += !(range.nearest == lo->depth && range.furthest == hi->depth);
        state scalar;
        placement.prepare_texel(in, scalar);
        std::vector<std::int32_t> layers(t.size(), -7);
        for (std::size_t i = 0; i < t.size(); ++i, ++fragments) layers[i] = placement.assign(scalar, t[i].depth);
        std::vector<std::int32_t> visited; // every fragment, with its layer or -1 (texel_assigner's)
        detail::for_each_layer(placement, scalar, in, instruction_set::scalar, [&](int k, const optical_fragment&) { visited.push_back(k); });
        differing_layers += visited != layers;
        std::array<std::uint32_t, K> expected{};
        for (const std::int32_t k : layers)
            if (k >= 0) ++expected[std::size_t(k)], ++layered;
        differing_counts += detail::layer_counts(placement, scalar, in, instruction_set::scalar) != expected;
#if HAIRSHADOW_AVX512_WALK // the vector members exist only where the vector paths are compiled
        if (!vector_half) continue;
        const detail::avx512::texel_scan scan = detail::avx512::texel_scan_of(in);
        differing_ranges += std::memcmp(&range, &scan.range, sizeof(range)) != 0;
        const bool one_b = std::all_of(t.begin(), t.end(), [&](const optical_fragment& f) { return f.optical_depth == t[0].optical_depth; });
        differing_one_b += scan.one_optical_depth != one_b;
        texels_of_one_b += one_b;
        state vector;
        placement.prepare_texel_avx512(in, vector);
        differing_states += std::memcmp(&scalar, &vector, sizeof(state)) != 0;
        std::vector<std::int32_t> vector_layers(t.size(), -7);
        placement.assign_texel_avx512(scalar, in, vector_layers.data());
        differing_layers += vector_layers != layers;
        // The grouped build's per-texel steps through their dispatch, against their scalar forms.
        state dispatched;
        detail::prepare_texel(placement, in, dispatched, instruction_set::avx512);
        differing_states += !(dispatched == scalar);
        std::vector<std::int32_t> visited_vector;
        detail::for_each_layer(placement, scalar, in, instruction_set::avx512, [&](int k, const optical_fragment&) { visited_vector.push_back(k); });
        differing_layers += visited_vector != visited;
        // The layers' counts (interpolation's build for a texel of one b), vector and dispatched.
        std::array<std::uint32_t, K> counted{};
        placement.count_texel_avx512(scalar, in, counted);
        differing_counts += counted != expected;
        differing_counts += detail::layer_counts(placement, scalar, in, instruction_set::avx512) != expected;
        // The texel as its depths alone (tile_fragments::group_depths, where a map has one b), against
        // its fragments all given the first one's b: the same range, state, counts and maps.
        std::vector<optical_fragment> one_of_b = t;
        std::vector<float> depths;
        for (auto& f : one_of_b) {
            f.optical_depth = t[0].optical_depth;
            depths.push_back(f.depth);
        }
        const std::span<const optical_fragment> uniform(one_of_b);
        const std::span<const float> alone(depths);
        const depth_extent alone_range = detail::avx512::texel_scan_of(alone).range;
        differing_ranges += std::memcmp(&range, &alone_range, sizeof(range)) != 0;
        state expected_state, from_depths;
        placement.prepare_texel(uniform, expected_state);
        placement.prepare_texel_depths_avx512(alone, t[0].optical_depth, from_depths);
        differing_states += std::memcmp(&expected_state, &from_depths, sizeof(state)) != 0;
        std::array<std::uint32_t, K> expected_alone{}, counted_alone{};
        for (const float d : depths)
            if (const int k = placement.assign(expected_state, d); k >= 0) ++expected_alone[std::size_t(k)];
        placement.count_texel_avx512(expected_state, alone, counted_alone);
        differing_counts += counted_alone != expected_alone;
        interpolation::storage<TestType, float_accumulation> built, built_alone;
        interpolation::build<TestType, float_accumulation>(placement, expected_state, uniform, built);
        interpolation::build_from_depths<TestType, float_accumulation>(placement, expected_state, alone, t[0].optical_depth, built_alone);
        differing_maps += std::memcmp(&built, &built_alone, sizeof(built)) != 0;
        ++texels_alone;
#endif
    }
    CHECK(fragments > 2000);
    CHECK(layered > 1000);
    CHECK(differing_counts == 0);
    CHECK(differing_ranges == 0);
    CHECK(differing_layers == 0);
    if (vector_half) {
        CHECK(differing_one_b == 0);
        CHECK(texels_of_one_b > 70);
        CHECK(differing_states == 0);
        CHECK(differing_maps == 0);
        CHECK(texels_alone == texels.size());
    }
}

TEST_CASE("a tile's depths grouped alone are its fragments' depths, texel by texel", "[tiled][avx512]") {
    // Grouping is plain C++; the build groups depths alone only where the vector walk runs (its half),
    // but the scalar walk's tiles are checked too.
    const bool vector_half = avx512_half_runs();
    const auto& model = test_model("curly");
    const auto light = light_space::fit(light_spec::directional({0.3f, -1, -0.5f}), model.bounds(), 256);
    for (const bool vector : {false, true}) {
        if (vector && !vector_half) continue;
        CAPTURE(vector);
        raster_options o;
        o.exec.threads = 2;
        o.instructions = vector ? instruction_set::avx512 : instruction_set::scalar;
        detail::tiled_workspace w;
        w.bins.prepare(model, light, o, true);
        REQUIRE(detail::tile_fragments::one_optical_depth(w.bins));
        const float b = optical_depth_of(w.bins.uniform_shader().shade(0.0f).alpha);
        std::vector<std::size_t> differing(detail::tile_slots(w), 0), compared(differing.size(), 0);
        detail::for_each_tile(
            w, detail::tile_grouping::on_demand,
            [&](unsigned slot, detail::tile_fragments& tile) {
                tile.group_depths();
                std::vector<std::vector<float>> alone;
                const texel_rect r = tile.rect();
                for (int y = r.y0; y < r.y1; ++y)
                    for (int x = r.x0; x < r.x1; ++x) alone.emplace_back(tile.texel_depths(x, y).begin(), tile.texel_depths(x, y).end());
                tile.group();
                std::size_t k = 0;
                for (int y = r.y0; y < r.y1; ++y)
                    for (int x = r.x0; x < r.x1; ++x, ++k) {
                        const auto whole = tile.texel(x, y);
                        differing[slot] += whole.size() != alone[k].size();
                        for (std::size_t i = 0; i < std::min(whole.size(), alone[k].size()); ++i, ++compared[slot])
                            differing[slot] += whole[i].depth != alone[k][i] || whole[i].optical_depth != b;
                    }
            },
            detail::fragment_order::any);
        CHECK(std::accumulate(compared.begin(), compared.end(), std::size_t(0)) > 100000);
        CHECK(std::accumulate(differing.begin(), differing.end(), std::size_t(0)) == 0);
        // A model of per-point transparency may have more than one b: its fragments are grouped whole.
        hair_model varied = model;
        varied.transparency.assign(varied.point_count(), 0.3f);
        w.bins.prepare(varied, light, o, false);
        CHECK_FALSE(detail::tile_fragments::one_optical_depth(w.bins));
    }
}

TEST_CASE("the instruction set resolves to what the CPU runs", "[tiled]") {
    CHECK(resolve(instruction_set::scalar) == instruction_set::scalar);
    const auto best = resolve(instruction_set::automatic);
    CHECK((best == instruction_set::avx512) == detail::cpu_has_avx512());
    if (detail::cpu_has_avx512()) CHECK(resolve(instruction_set::avx512) == instruction_set::avx512);
    else CHECK_THROWS_AS(resolve(instruction_set::avx512), argument_error);
    raster_options bad;
    bad.tile_size = 4;
    deep_opacity_maps<3> dom;
    CHECK_THROWS_AS(dom.build(test_model("sintel"), light_space::fit(light_spec::directional({0, -1, 0}), test_model("sintel").bounds(), 64), bad),
                    argument_error);
}

TEST_CASE("the thread pool runs nested and concurrent loops and passes exceptions on", "[parallel]") {
    std::vector<int> hits(1000, 0);
    parallel_for(10, execution{4}, [&](std::size_t i) {
        parallel_for(100, execution{4}, [&](std::size_t j) { ++hits[i * 100 + j]; }); // nested: runs on the calling thread
    });
    CHECK(std::count(hits.begin(), hits.end(), 1) == 1000);

    std::atomic<int> total{0};
    std::thread other([&] { parallel_for(5000, execution{3}, [&](std::size_t) { ++total; }); });
    parallel_for(5000, execution{3}, [&](std::size_t) { ++total; });
    other.join();
    CHECK(total == 10000);

    CHECK_THROWS_AS(parallel_for(100, execution{4}, [](std::size_t i) {
                        if (i == 57) throw argument_error("item 57");
                    }),
                    argument_error);
    // The pool still works after a failed loop.
    std::atomic<int> after{0};
    parallel_for(64, execution{8}, [&](std::size_t) { ++after; });
    CHECK(after == 64);
    // Slots tell the threads of one loop apart.
    std::vector<std::atomic<int>> in_use(parallel_slots(1000, execution{3}));
    std::atomic<bool> shared{false};
    parallel_for_slots(1000, execution{3}, [&](unsigned slot, std::size_t) {
        if (in_use[slot].fetch_add(1) != 0) shared = true;
        in_use[slot].fetch_sub(1);
    });
    CHECK_FALSE(shared);
}

TEST_CASE("the compositions that reduce texel by texel build without grouping fragments", "[tiled]") {
    // methods/streamed_tile.hpp: the interpolated methods (OSM, DOM, ROSM and their hybrids) and the
    // occupancy maps stream, DC and the fibre densities group; the bit-for-bit test above covers both.
    STATIC_REQUIRE(detail::streams_tiles<planar_slices<16, uniform_spacing>, float_accumulation, interpolation>);
    STATIC_REQUIRE(detail::streams_tiles<per_pixel_depth<3>, emulated_8bit, interpolation>);
    STATIC_REQUIRE(detail::streams_tiles<depth_range<16>, float_accumulation, interpolation>);
    STATIC_REQUIRE(detail::streams_tiles<per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation, interpolation>);
    STATIC_REQUIRE(detail::streams_tiles<depth_range<128>, float_accumulation, occupancy_bitcount<4>>);
    STATIC_REQUIRE(detail::streams_tiles<per_pixel_depth<128>, emulated_8bit, occupancy_bitcount<1>>);
    STATIC_REQUIRE_FALSE(detail::streams_tiles<clustered<4>, float_accumulation, interpolation>);
    STATIC_REQUIRE_FALSE(detail::streams_tiles<per_pixel_depth<1>, float_accumulation, fibre_density<fibre_density_source::fixed>>);
#if HAIRSHADOW_AVX512_WALK
    // Density clustering groups the depths alone where a map has one b (tile_fragments::group_depths).
    STATIC_REQUIRE(detail::builds_from_depths_avx512<clustered<4>, float_accumulation, interpolation>);
    STATIC_REQUIRE(detail::builds_from_depths_avx512<clustered<3>, emulated_8bit, interpolation>);
    STATIC_REQUIRE_FALSE(detail::builds_from_depths_avx512<per_pixel_depth<1>, float_accumulation, fibre_density<fibre_density_source::fixed>>);
#endif
}
