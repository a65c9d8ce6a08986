#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <utility>

using namespace hairshadow;

namespace {

using texel = std::pair<int, int>;

fixed_point at(double x, double y) { return {std::llround(x * subpixel_scale), std::llround(y * subpixel_scale)}; }

std::set<texel> fragments_of(fixed_point a, fixed_point b, texel_rect clip = {-64, -64, 64, 64}) {
    std::set<texel> out;
    std::size_t count = 0;
    rasterize_line(a, b, clip, [&](int x, int y) {
        out.insert({x, y});
        ++count;
    });
    REQUIRE(count == out.size()); // never the same texel twice
    return out;
}

/// The diamond-exit rule straight from the GL specification's wording, by brute force over candidate
/// texels, with the perturbation -(e, e^2) made concrete: coordinates are scaled by 2^40 and moved by
/// -2^20 and -1 units, which no tie in the scaled problem can survive. Independent of rasterize_line.
std::set<texel> diamond_exit_brute_force(fixed_point a, fixed_point b) {
    __extension__ typedef __int128 i128;
    const i128 K = i128(1) << 40, S = subpixel_scale;
    const i128 ax = a.x * K - (i128(1) << 20), ay = a.y * K - 1, bx = b.x * K - (i128(1) << 20), by = b.y * K - 1;
    const i128 R = S / 2 * K;
    auto abs128 = [](i128 v) { return v < 0 ? -v : v; };
    std::set<texel> out;
    const auto lo_x = std::min(a.x, b.x) / S - 2, hi_x = std::max(a.x, b.x) / S + 2;
    const auto lo_y = std::min(a.y, b.y) / S - 2, hi_y = std::max(a.y, b.y) / S + 2;
    for (auto y = lo_y; y <= hi_y; ++y)
        for (auto x = lo_x; x <= hi_x; ++x) {
            const i128 cx = (i128(x) * S + S / 2) * K, cy = (i128(y) * S + S / 2) * K;
            if (abs128(bx - cx) + abs128(by - cy) < R) continue; // the segment ends inside: not produced
            // Rotate by 45 degrees: the diamond becomes the open square |s| < R, |t| < R.
            const i128 sa = (ax - cx) + (ay - cy), ta = (ax - cx) - (ay - cy);
            const i128 sb = (bx - cx) + (by - cy), tb = (bx - cx) - (by - cy);
            if (std::max(sa, sb) <= -R || std::min(sa, sb) >= R || std::max(ta, tb) <= -R || std::min(ta, tb) >= R) continue;
            int positive = 0, negative = 0;
            for (const i128 cs : {-R, R})
                for (const i128 ct : {-R, R}) {
                    const i128 cross = (sb - sa) * (ct - ta) - (tb - ta) * (cs - sa);
                    positive += cross > 0;
                    negative += cross < 0;
                }
            if (positive == 4 || negative == 4) continue; // the segment's line misses the square
            out.insert({int(x), int(y)});
        }
    return out;
}

} // namespace

TEST_CASE("hand-worked segments give the hand-computed fragments", "[raster][line]") {
    // Centre to centre: the first texel is left, so it is drawn; the last is not.
    CHECK(fragments_of(at(0.5, 0.5), at(4.5, 0.5)) == std::set<texel>{{0, 0}, {1, 0}, {2, 0}, {3, 0}});
    // The same segment reversed: the texel it starts in is drawn, the one it ends in is not.
    CHECK(fragments_of(at(4.5, 0.5), at(0.5, 0.5)) == std::set<texel>{{1, 0}, {2, 0}, {3, 0}, {4, 0}});
    // A diagonal from corner to corner.
    CHECK(fragments_of(at(0, 0), at(3, 3)) == std::set<texel>{{0, 0}, {1, 1}, {2, 2}});
    // Along a row of texel corners: the perturbation lowers the line into the row below; it starts
    // left of the first diamond's top vertex and ends left of the last one's.
    CHECK(fragments_of(at(0.5, 1.0), at(4.5, 1.0)) == std::set<texel>{{0, 0}, {1, 0}, {2, 0}, {3, 0}});
    // Along a column of texel corners: the perturbation moves the line into the column on the left.
    CHECK(fragments_of(at(2.0, 0.5), at(2.0, 3.5)) == std::set<texel>{{1, 0}, {1, 1}, {1, 2}});
    // A short vertical segment that ends inside the diamond it entered draws nothing...
    CHECK(fragments_of(at(2.5, 0.2), at(2.5, 0.8)).empty());
    // ...and one that leaves it draws that texel.
    CHECK(fragments_of(at(2.5, 0.2), at(2.5, 1.2)) == std::set<texel>{{2, 0}});
    // A steep line: one fragment per row.
    CHECK(fragments_of(at(1.25, 0.5), at(2.75, 3.5)) == std::set<texel>{{1, 0}, {1, 1}, {2, 2}});
    // Zero length: nothing.
    CHECK(fragments_of(at(1.5, 1.5), at(1.5, 1.5)).empty());
}

TEST_CASE("the clip rectangle keeps exactly the fragments inside it", "[raster][line]") {
    const auto a = at(0.3, 0.7), b = at(30.6, 9.2);
    const auto all = fragments_of(a, b);
    const texel_rect clip{5, 2, 17, 6};
    std::set<texel> expected;
    for (const auto& t : all)
        if (clip.contains(t.first, t.second)) expected.insert(t);
    CHECK(fragments_of(a, b, clip) == expected);
}

TEST_CASE("the line rule equals a brute-force reading of the GL specification", "[raster][line]") {
    random_stream rng(12345);
    // Coordinates on coarse grids (texel corners, centres, quarters) hit the boundary cases the
    // perturbation decides; fine ones cover the general case.
    const int grids[] = {128, 64, 32, 1};
    for (int i = 0; i < 20000; ++i) {
        const int g = grids[i % 4];
        auto coord = [&] { return std::int64_t(rng.uniform(-6.0f, 14.0f) * float(subpixel_scale) / float(g)) * g; };
        fixed_point a{coord(), coord()}, b{coord(), coord()};
        if (i % 7 == 0) b.y = a.y;                       // horizontal
        if (i % 11 == 0) b.x = a.x;                      // vertical
        if (i % 13 == 0) b = {a.x + (b.x - a.x), a.y + (b.x - a.x)}; // exact diagonal
        CAPTURE(a.x, a.y, b.x, b.y);
        REQUIRE(fragments_of(a, b) == diamond_exit_brute_force(a, b));
    }
}
