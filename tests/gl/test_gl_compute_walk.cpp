// The compute build's line rule (hs_walk in shaders/compute/common.glsl, 32-bit words) against the
// CPU's rasterize_line (32-bit words too, its set-up's quotients by 64-bit division), segment by segment: the same fragments, in the same order,
// for short segments on the grids where the perturbation decides ties, and for segments up to the
// guard band's length, where the walk's products no longer fit 32 bits and it takes its long path.
#include <glad/gl.h>

#include <hairshadow/gl.hpp>

#include "gl_test_context.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

using namespace hairshadow;

namespace {

/// A segment's snapped ends (sub-pixels) and the clip rectangle it is walked in.
struct walk_case {
    std::array<std::int32_t, 4> ends; // ax, ay, bx, by
    texel_rect clip;
};

/// Fragments as (case index, x, y), in the order each case emits them.
using fragment_list = std::vector<std::array<std::int32_t, 3>>;

fragment_list walk_on_cpu(const std::vector<walk_case>& cases) {
    fragment_list out;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& e = cases[i].ends;
        rasterize_line(fixed_point{e[0], e[1]}, fixed_point{e[2], e[3]}, cases[i].clip,
                       [&](int x, int y) { out.push_back({std::int32_t(i), x, y}); });
    }
    return out;
}

/// The same on the GPU: one invocation per case, each appending its fragments to its own run of the
/// output (runs sized by the CPU's counts plus slack, so a walk that makes more still shows).
fragment_list walk_on_gpu(const std::vector<walk_case>& cases, const fragment_list& expected) {
    test::gl_context();
    std::vector<std::int32_t> input;
    std::vector<std::uint32_t> first{0};
    std::vector<std::uint32_t> count_of(cases.size(), 0);
    for (const auto& f : expected) ++count_of[std::size_t(f[0])];
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const auto& c = cases[i];
        input.insert(input.end(), c.ends.begin(), c.ends.end());
        input.insert(input.end(), {c.clip.x0, c.clip.y0, c.clip.x1, c.clip.y1});
        first.push_back(first.back() + count_of[i] + 4);
    }
    const std::string_view body = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 4) readonly buffer hs_case_block { ivec4 hs_cases[]; };        // ends, clip
layout(std430, binding = 5) readonly buffer hs_first_block { uint hs_first[]; };        // each case's run
layout(std430, binding = 6) writeonly buffer hs_out_block { ivec2 hs_out[]; };
layout(std430, binding = 7) writeonly buffer hs_count_block { uint hs_out_count[]; };
uniform uint hs_case_count;
uint hs_case, hs_made;
void hs_emit(int x, int y) {
    if (hs_first[hs_case] + hs_made < hs_first[hs_case + 1u]) hs_out[hs_first[hs_case] + hs_made] = ivec2(x, y);
    ++hs_made;
}
void main() {
    hs_case = gl_GlobalInvocationID.x;
    if (hs_case >= hs_case_count) return;
    hs_made = 0u;
    hs_walk(hs_cases[2u * hs_case].xy, hs_cases[2u * hs_case].zw, hs_cases[2u * hs_case + 1u]);
    hs_out_count[hs_case] = hs_made;
}
)";
    auto pieces = gl::detail::compute_pieces("");
    pieces.push_back(body);
    const auto stage = gl::compile_stage(GL_COMPUTE_SHADER, {}, pieces, "compute walk test");
    const auto program = gl::link_program({&stage}, "compute walk test");
    auto in = gl::make_buffer(), runs = gl::make_buffer(), out = gl::make_buffer(), counts = gl::make_buffer();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, in.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(input.size() * 4), input.data(), GL_STATIC_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, runs.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(first.size() * 4), first.data(), GL_STATIC_DRAW);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, out.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(std::size_t(first.back()) * 8), nullptr, GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, counts.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(cases.size() * 4), nullptr, GL_DYNAMIC_READ);
    glUseProgram(program.get());
    glUniform1ui(glGetUniformLocation(program.get(), "hs_case_count"), std::uint32_t(cases.size()));
    glDispatchCompute(std::uint32_t(cases.size() + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::int32_t> xy(2 * std::size_t(first.back()));
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, out.get());
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(xy.size() * 4), xy.data());
    std::vector<std::uint32_t> made(cases.size());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, counts.get());
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(made.size() * 4), made.data());
    glUseProgram(0);
    REQUIRE(glGetError() == GL_NO_ERROR);
    fragment_list result;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::uint32_t kept = std::min(made[i], first[i + 1] - first[i]);
        for (std::uint32_t j = 0; j < kept; ++j)
            result.push_back({std::int32_t(i), xy[2 * (first[i] + j)], xy[2 * (first[i] + j) + 1]});
        for (std::uint32_t j = kept; j < made[i]; ++j) result.push_back({std::int32_t(i), -1, -1}); // past the slack
    }
    return result;
}

void require_same_walks(const std::vector<walk_case>& cases) {
    test::gl_context();
    REQUIRE(gl::compute_path_missing().empty());
    const fragment_list cpu = walk_on_cpu(cases), gpu = walk_on_gpu(cases, cpu);
    std::vector<bool> made(cases.size());
    for (const auto& f : cpu) made[std::size_t(f[0])] = true;
    CHECK(std::count(made.begin(), made.end(), true) > std::ptrdiff_t(cases.size()) / 2); // most cases walk fragments inside their clips
    if (cpu == gpu) return;
    const auto [c, g] = std::mismatch(cpu.begin(), cpu.end(), gpu.begin(), gpu.end());
    // The first case whose fragments differ (an extra fragment at a case's end shifts the next case's).
    const auto at = std::min(c != cpu.end() ? (*c)[0] : std::int32_t(cases.size()), g != gpu.end() ? (*g)[0] : std::int32_t(cases.size()));
    const auto& e = cases[std::size_t(at)].ends;
    const auto& r = cases[std::size_t(at)].clip;
    CAPTURE(at, e[0], e[1], e[2], e[3], r.x0, r.y0, r.x1, r.y1);
    CAPTURE(c != cpu.end() ? (*c)[1] : -2, c != cpu.end() ? (*c)[2] : -2, g != gpu.end() ? (*g)[1] : -2, g != gpu.end() ? (*g)[2] : -2);
    FAIL("the compute walk's fragments differ from rasterize_line's (first difference above: CPU x, y then GPU x, y)");
}

constexpr std::int32_t S = std::int32_t(subpixel_scale);
constexpr std::int32_t band = std::int32_t(1) << 20; // detail::guard_band, in texels

/// A clip of `side` texels around the point a + f (b - a), within the band.
texel_rect clip_around(const std::array<std::int32_t, 4>& e, double f, int side) {
    const double x = (e[0] + f * (double(e[2]) - e[0])) / S, y = (e[1] + f * (double(e[3]) - e[1])) / S;
    const int x0 = std::clamp(int(std::floor(x)) - side / 2, -band, band - side), y0 = std::clamp(int(std::floor(y)) - side / 2, -band, band - side);
    return {x0, y0, x0 + side, y0 + side};
}

/// |o d_minor| of the walk's first division (hs_product_quotient): o is the first centre's distance
/// from the start along the major axis, 0 when the clip leaves no centre.
double starting_product(const walk_case& c) {
    const fixed_point a{c.ends[0], c.ends[1]}, b{c.ends[2], c.ends[3]};
    if (a == b) return 0.0;
    const auto w = detail::set_up_line(a, b, c.clip);
    if (w.m_begin > w.m_end) return 0.0;
    const double major_a = w.x_major ? double(a.x) : double(a.y);
    const double d_minor = w.x_major ? double(b.y - a.y) : double(b.x - a.x);
    return std::abs(double(w.m_begin) * S + S / 2 - major_a) * std::abs(d_minor);
}

} // namespace

TEST_CASE("the compute walk makes rasterize_line's fragments for short segments on tie grids", "[gl][compute][line]") {
    // The brute-force test's distribution (test_line_rule.cpp): ends on texel corners, centres and
    // quarters, and anywhere, with horizontal, vertical and exact diagonal segments.
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> texels(-6.0, 14.0);
    const int grids[] = {128, 64, 32, 1};
    std::vector<walk_case> cases;
    for (int i = 0; i < 20000; ++i) {
        const int g = std::max(grids[i % 4] * S / 256, 1); // in sub-pixels: half, quarter, eighth texels, or any
        auto coord = [&] { return std::int32_t(texels(random) * S / g) * g; };
        std::array<std::int32_t, 4> e{};
        for (auto& v : e) v = coord();
        if (i % 7 == 0) e[3] = e[1];
        if (i % 11 == 0) e[2] = e[0];
        if (i % 13 == 0) e[3] = e[1] + (e[2] - e[0]);
        // The whole neighbourhood, or a clip that cuts the walk on either axis.
        const texel_rect clip = i % 3 == 0 ? texel_rect{-8, -8, 16, 16} : texel_rect{int(random() % 8) - 4, int(random() % 8) - 4, int(random() % 8) + 4, int(random() % 8) + 4};
        cases.push_back({e, clip});
    }
    require_same_walks(cases);
}

TEST_CASE("the compute walk makes rasterize_line's fragments for segments up to the guard band", "[gl][compute][line]") {
    // Lengths spread over every scale up to the band's diagonal, so that both of the walk's divisions
    // (one word, and the long multiplication where |o d_minor| passes 2^32) run; ends snapped to
    // texel centres or corners in a quarter of them, where ties are decided; clips of 24 texels where
    // the segment passes, somewhere along it.
    std::mt19937 random(4343);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<walk_case> cases;
    int long_products = 0;
    for (int i = 0; i < 20000; ++i) {
        const double length = std::exp2(unit(random) * 29.0) * (S / 256.0); // sub-pixels, up to 2^29 at 8 bits
        const double angle = unit(random) * 6.283185307179586;
        const std::int32_t limit = band * S;
        std::array<std::int32_t, 4> e{};
        e[0] = std::int32_t((unit(random) * 2.0 - 1.0) * limit);
        e[1] = std::int32_t((unit(random) * 2.0 - 1.0) * limit);
        e[2] = std::int32_t(std::clamp(e[0] + length * std::cos(angle), -double(limit), double(limit)));
        e[3] = std::int32_t(std::clamp(e[1] + length * std::sin(angle), -double(limit), double(limit)));
        if (i % 4 == 0)
            for (auto& v : e) v = v / (S / 2) * (S / 2); // centres and corners
        if (i % 17 == 0) e[3] = e[1];
        if (i % 19 == 0) e[2] = e[0];
        if (i % 23 == 0) { // an exact diagonal, within the band
            const std::int32_t d = std::min(std::abs(e[2] - e[0]), limit - std::abs(e[1]));
            e[3] = e[1] + (e[1] > 0 ? -d : d);
        }
        if (i % 101 == 0) e = {-limit, -limit, limit, limit - S * (i % 7)}; // across the whole band
        const walk_case c{e, clip_around(e, unit(random), 24)};
        if (starting_product(c) >= 4294967296.0) ++long_products;
        cases.push_back(c);
    }
    CHECK(long_products > 2000); // the long multiplication is exercised, not just the one-word division
    require_same_walks(cases);
}
