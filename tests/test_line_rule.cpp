#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

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

/// The line rule as it was before issue 43, in 64-bit integers (the minor coordinate at a centre as
/// n + rem / (|d_major| S)): the oracle that the 32-bit rule (k + r / |d_major| sub-pixels) must
/// equal fragment for fragment, in order.
namespace rule64 {
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}
std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return -floor_div(-a, b); }
bool inside_diamond(const fixed_point& p, std::int64_t c, std::int64_t r) {
    constexpr std::int64_t half = subpixel_scale / 2;
    const std::int64_t u = p.x - (c * subpixel_scale + half), v = p.y - (r * subpixel_scale + half);
    const std::int64_t l1 = std::llabs(u) + std::llabs(v);
    return l1 < half || (l1 == half && u > 0);
}
template <class Emit>
void rasterize_line(const fixed_point& a, const fixed_point& b, const texel_rect& clip, Emit&& emit) {
    constexpr std::int64_t S = subpixel_scale, H = subpixel_scale / 2;
    if (a == b) return;
    const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
    const bool x_major = std::llabs(dx) >= std::llabs(dy);
    const std::int64_t major_a = x_major ? a.x : a.y, major_b = x_major ? b.x : b.y;
    const std::int64_t d_major = x_major ? dx : dy, d_minor = x_major ? dy : dx, minor_a = x_major ? a.y : a.x;
    const std::int64_t lo_end = d_major > 0 ? major_a : major_b, hi_end = d_major > 0 ? major_b : major_a;
    const std::int64_t first = ceil_div(lo_end - H, S), last = ceil_div(hi_end - H, S) - 1;
    const std::int64_t m_begin = std::max<std::int64_t>(first, x_major ? clip.x0 : clip.y0);
    const std::int64_t m_end = std::min<std::int64_t>(last, (x_major ? clip.x1 : clip.y1) - 1);
    const std::int64_t denom = (d_major > 0 ? d_major : -d_major) * S, sign = d_major > 0 ? 1 : -1;
    const bool lower_on_tie = !x_major || dy == 0 || (dx > 0) != (dy > 0);
    if (m_begin <= m_end) {
        const std::int64_t num0 = sign * (minor_a * d_major + (m_begin * S + H - major_a) * d_minor);
        std::int64_t n = floor_div(num0, denom), rem = num0 - n * denom;
        const std::int64_t step = sign * d_minor * S;
        const std::int64_t step_q = step == denom ? 1 : (step < 0 ? -1 : 0), step_r = step - step_q * denom;
        for (std::int64_t m = m_begin; m <= m_end; ++m) {
            const std::int64_t minor = (lower_on_tie && rem == 0) ? n - 1 : n;
            const std::int64_t x = x_major ? m : minor, y = x_major ? minor : m;
            if (clip.contains(x, y) && !inside_diamond(b, x, y)) emit(int(x), int(y));
            n += step_q;
            rem += step_r;
            if (rem >= denom) rem -= denom, ++n;
        }
    }
    const std::int64_t ax = floor_div(a.x - 1, S), ay = floor_div(a.y - 1, S), a_major = x_major ? ax : ay;
    if (inside_diamond(a, ax, ay) && (a_major < first || a_major > last) && !inside_diamond(b, ax, ay) && clip.contains(ax, ay))
        emit(int(ax), int(ay));
}
} // namespace rule64

/// Segments whose fragments by rasterize_line and walk_line (its kept ones) differ from rule64's, in
/// order; reports the first few.
std::size_t differing(const std::vector<std::pair<fixed_point, fixed_point>>& segments, const texel_rect& clip) {
    std::size_t wrong = 0;
    std::vector<std::array<int, 2>> expected, line, walked;
    for (const auto& [a, b] : segments) {
        expected.clear(), line.clear(), walked.clear();
        rule64::rasterize_line(a, b, clip, [&](int x, int y) { expected.push_back({x, y}); });
        rasterize_line(a, b, clip, [&](int x, int y) { line.push_back({x, y}); });
        walk_line(a, b, clip, [&](int x, int y, bool keep) {
            if (keep) walked.push_back({x, y});
        });
        if ((line != expected || walked != expected) && ++wrong <= 3)
            UNSCOPED_INFO("(" << a.x << ", " << a.y << ") -> (" << b.x << ", " << b.y << "): " << expected.size() << " fragments by the 64-bit rule, "
                              << line.size() << " by rasterize_line, " << walked.size() << " kept by walk_line");
    }
    return wrong;
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

TEST_CASE("the 32-bit line rule gives the 64-bit rule's fragments, in order", "[raster][line]") {
    // The brute-force test's segments (tie grids, horizontals, verticals, diagonals), clipped and not.
    random_stream rng(12345);
    const int grids[] = {128, 64, 32, 1};
    std::vector<std::pair<fixed_point, fixed_point>> segments;
    for (int i = 0; i < 20000; ++i) {
        const int g = grids[i % 4];
        auto coord = [&] { return std::int64_t(rng.uniform(-6.0f, 14.0f) * float(subpixel_scale) / float(g)) * g; };
        fixed_point a{coord(), coord()}, b{coord(), coord()};
        if (i % 7 == 0) b.y = a.y;
        if (i % 11 == 0) b.x = a.x;
        if (i % 13 == 0) b = {a.x + (b.x - a.x), a.y + (b.x - a.x)};
        segments.push_back({a, b});
    }
    CHECK(differing(segments, {-64, -64, 64, 64}) == 0);
    CHECK(differing(segments, {2, -1, 7, 5}) == 0);
    // Segments of every length up to the guard band's diagonal, where the set-up's products need 64
    // bits: ends anywhere in the band, a quarter of them on texel-centre or corner grids, walked
    // through a 24-texel clip on their path.
    std::mt19937 random(4304);
    const std::int64_t band = std::int64_t(1 << 20) * subpixel_scale;
    std::uniform_int_distribution<std::int64_t> anywhere(-band, band);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t wrong = 0;
    for (int i = 0; i < 20000; ++i) {
        const double length = std::exp2(unit(random) * 30.0);
        fixed_point a{anywhere(random), anywhere(random)};
        const double angle = unit(random) * 6.283185307179586;
        fixed_point b{std::clamp<std::int64_t>(a.x + std::int64_t(length * std::cos(angle)), -band, band),
                      std::clamp<std::int64_t>(a.y + std::int64_t(length * std::sin(angle)), -band, band)};
        if (i % 4 == 0) { // on grids of centres (odd multiples of H) or corners
            const std::int64_t g = i % 8 == 0 ? subpixel_scale : subpixel_scale / 2;
            a = {a.x / g * g, a.y / g * g}, b = {b.x / g * g, b.y / g * g};
        }
        const double s = unit(random);
        const int cx = int(std::floor((double(a.x) + s * double(b.x - a.x)) / double(subpixel_scale)));
        const int cy = int(std::floor((double(a.y) + s * double(b.y - a.y)) / double(subpixel_scale)));
        wrong += differing({{a, b}}, {cx - 12, cy - 12, cx + 12, cy + 12});
    }
    CHECK(wrong == 0);
    // Every segment of the Sintel hair and of a curly model as the rasteriser prepares them, under a
    // directional light and a spot light, over the whole map.
    for (const auto& model : {read_tfx(test::sintel_hair()), load_model("procedural:curly:strands=2000:segments=100")}) {
        const aabb box = model.bounds();
        const glm::vec3 centre = box.center(), size = box.extent();
        for (const auto& spec : {light_spec::directional({0.3f, -1, -0.5f}), light_spec::spot(centre + glm::vec3(0, 0, size.z), {0, 0, -1}, 40.0f)}) {
            const auto ls = light_space::fit(spec, model.bounds(), 1024);
            segments.clear();
            for (std::size_t strand = 0; strand < model.strand_count(); ++strand) {
                const std::size_t p0 = model.strand_offsets[strand], n = model.strand_size(strand);
                for (std::size_t i = 0; i + 1 < n; ++i) {
                    const glm::vec3 p = model.points[p0 + i], q = model.points[p0 + i + 1];
                    detail::segment_attributes at{0.001f, 0.001f, 1.0f, 1.0f};
                    detail::prepared_segment s{};
                    if (detail::prepare_segment(ls, p, q, detail::project_point(ls, p), detail::project_point(ls, q), at, s))
                        segments.push_back({s.a(), s.b()});
                }
            }
            CHECK(segments.size() > 100000);
            CHECK(differing(segments, {0, 0, 1024, 1024}) == 0);
        }
    }
}
