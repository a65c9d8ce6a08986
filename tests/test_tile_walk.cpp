// The tiled build's raster stages: projection and binning, the line walk against the line rule, the
// tiles' fragment bounds, the AVX-512 walks against the scalar walk, a tile's depths grouped alone,
// and the instruction set chosen.
#include "tiled_build_support.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <numeric>
#include <optional>
#include <random>
#include <set>
#include <thread>
#include <tuple>

using namespace hairshadow;
using namespace test;

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
    const auto optical_depths = [](const detail::tile_fragments& f) {
        std::vector<float> out(f.size());
        for (std::size_t i = 0; i < f.size(); ++i) out[i] = f.walk_optical_depth(i);
        return out;
    };
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
                                       same(optical_depths(scalar), optical_depths(vector)));
                        // The vector walk keeps its tiles' one optical depth once, the scalar walk one a fragment.
                        CHECK_FALSE(scalar.tile_optical_depth());
                        REQUIRE(detail::tile_fragments::one_optical_depth(bins));
                        CHECK(vector.tile_optical_depth() == std::optional<float>(detail::tile_fragments::shared_optical_depth(bins)));
                        CHECK(vector.walk_optical_depths().empty());
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
        for (std::size_t i = 0; i < f.size(); ++i) out.emplace_back(f.walk_texels()[i], f.walk_depths()[i], f.walk_optical_depth(i));
        return out;
    };
    // Every tile size at 96x96; at 512x512 (the slow part under the sanitizers) the default tile and
    // one whose side is no power of two.
    const std::pair<int, int> sizes[] = {{96, 8}, {96, 16}, {96, 37}, {96, 64}, {96, 200}, {512, 37}, {512, 64}};
    std::size_t sorted_tiles = 0, listed_tiles = 0; // walked sorted by their steps, walked in list order
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
                std::size_t fragments = 0, reordered = 0, differing = 0, unstable = 0, sorted_here = 0;
                for (std::size_t t = 0; t < bins.tile_count(); ++t) {
                    in_order.gather(bins, t, instruction_set::scalar);
                    any.gather(bins, t, instruction_set::avx512, detail::fragment_order::any);
                    auto expected = fragments_of(in_order), got = fragments_of(any);
                    walked[t] = got;
#if HAIRSHADOW_AVX512_WALK
                    if (bins.tile_segments(t).size() > 16) {
                        const bool sorts = detail::avx512::tile_walk::sorting_pays(bins, t);
                        (sorts ? sorted_tiles : listed_tiles) += 1;
                        sorted_here += sorts;
                    }
#endif
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
                // The test walks the other order, not segment order again; under the spot light, lanes whose
                // ends differ in 1/w walk apart, in segment order, and a tile walked in list order may keep it.
                if (spec == &ortho || sorted_here > 0) CHECK(reordered > 0);
            }
    // Both orders of the walk were checked.
    if (vector_half) CHECK((sorted_tiles > 0 && listed_tiles > 0));
}

#if HAIRSHADOW_AVX512_WALK
TEST_CASE("the walk in any order sorts a tile's segments by their steps only where list order would waste steps", "[tiled][raster][avx512]") {
    if (!avx512_half_runs()) return;
    // Short segments against the texels (curly at 512x512): list order wastes little; long ones (at
    // 2048x2048 the same segments cross four times the texels, and a tile cuts more of them short):
    // their lengths in a tile spread, and sorting pays.
    const auto& model = test_model("curly");
    const auto sorted_share = [&](int res) {
        detail::segment_bins bins;
        bins.prepare(model, light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), res), raster_options{});
        std::size_t sorted = 0, walked = 0;
        for (std::size_t t = 0; t < bins.tile_count(); ++t)
            if (bins.tile_segments(t).size() > 16) sorted += detail::avx512::tile_walk::sorting_pays(bins, t), ++walked;
        REQUIRE(walked > 10);
        return double(sorted) / double(walked);
    };
    const double at_512 = sorted_share(512), at_2048 = sorted_share(2048);
    CAPTURE(at_512, at_2048);
    CHECK(at_512 < 0.1);
    CHECK(at_2048 > 0.9);
}
#endif

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
