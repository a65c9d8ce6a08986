// shaders/arithmetic/fixed_point.glsl and exact_square_root.glsl in llvmpipe: the 32-bit word arithmetic
// that lets density clustering's compute pass give the CPU's means and deviations with no double
// precision or 64-bit integers. Each function against the CPU operation it stands for, bit for bit,
// on values that reach every branch (saturation, subnormals, NaN and infinities included).
#include <glad/gl.h>

#include <hairshadow/gl.hpp>

#include "gl_test_context.hpp"

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace hairshadow;

namespace {

/// Runs `statement` (GLSL that reads `word`, an item's pair of words, and sets `result`) for every
/// pair of words in `in`; returns the results, two words an item.
std::vector<std::uint32_t> run_on_gpu(const std::vector<std::uint32_t>& in, const std::string& statement) {
    const std::string body = R"(
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= hs_count) return;
    uvec2 word = uvec2(hs_in[2u * i], hs_in[2u * i + 1u]);
    uvec2 result = uvec2(0u);
    )" + statement + R"(;
    hs_out[2u * i] = result.x;
    hs_out[2u * i + 1u] = result.y;
}
)";
    return test::run_on_words("", {gl::shaders::arithmetic_exact_division, gl::shaders::arithmetic_fixed_point, gl::shaders::arithmetic_exact_square_root},
                              body, in, std::uint32_t(in.size() / 2), "fixed point test");
}

/// Floats of every kind: specials, random bit patterns (any exponent, subnormals), and values near 1.
std::vector<float> test_floats(std::mt19937& random, int count) {
    std::vector<float> out{0.0f,
                           -0.0f,
                           1.0f,
                           -1.0f,
                           0.5f,
                           7.0f,
                           std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::quiet_NaN(),
                           std::numeric_limits<float>::denorm_min(),
                           test::from_bits(0x007fffffu),
                           std::numeric_limits<float>::min(),
                           std::numeric_limits<float>::max(),
                           std::nextafter(1.0f, 2.0f),
                           std::nextafter(1.0f, 0.0f),
                           16777215.0f,
                           0x1p27f,
                           0x1p-36f};
    std::uniform_int_distribution<std::uint32_t> any;
    std::uniform_real_distribution<float> near_one(-2.0f, 2.0f);
    while (int(out.size()) < count) {
        out.push_back(test::from_bits(any(random)));
        out.push_back(near_one(random));
    }
    return out;
}

} // namespace

TEST_CASE("hs_fixed_product gives clustered::fixed_sum of the two floats' product", "[gl][compute][fixed]") {
    std::mt19937 random(4301);
    const auto floats = test_floats(random, 200);
    std::vector<std::uint32_t> pairs;
    const auto add = [&](float a, float b) { pairs.push_back(test::bits_of(a)), pairs.push_back(test::bits_of(b)); };
    for (float a : floats)
        for (float b : floats) add(a, b);
    // Products at the edges of the shifts: each exponent sum from far below 2^-36 (zero) to past 2^27
    // (saturated), with random significands and signs.
    std::uniform_int_distribution<std::uint32_t> significand(0, 0x7fffffu), sign(0, 1);
    for (int ea = 1; ea < 255; ea += 3)
        for (int eb = 1; eb < 255; eb += 2) {
            const float a = test::from_bits(sign(random) << 31 | std::uint32_t(ea) << 23 | significand(random));
            add(a, test::from_bits(sign(random) << 31 | std::uint32_t(eb) << 23 | significand(random)));
        }
    const auto gpu = run_on_gpu(pairs, "result = hs_fixed_product(uintBitsToFloat(word.x), uintBitsToFloat(word.y))");
    std::size_t wrong = 0, saturated = 0, zero = 0, between = 0;
    for (std::size_t i = 0; i < pairs.size(); i += 2) {
        const std::int64_t expected = clustered<1>::fixed_sum(double(test::from_bits(pairs[i])) * double(test::from_bits(pairs[i + 1])));
        const auto got = std::int64_t(std::uint64_t(gpu[i]) | std::uint64_t(gpu[i + 1]) << 32);
        saturated += expected == std::numeric_limits<std::int64_t>::max() || expected == -std::numeric_limits<std::int64_t>::max();
        zero += expected == 0;
        between += std::abs(double(expected)) > 1.0 && std::abs(double(expected)) < 0x1p62;
        if (got != expected && ++wrong <= 3)
            UNSCOPED_INFO(std::hexfloat << test::from_bits(pairs[i]) << " * " << test::from_bits(pairs[i + 1]) << ": CPU " << expected << ", GPU " << got);
    }
    CHECK(wrong == 0);
    CHECK(saturated > 1000); // every branch was reached
    CHECK(zero > 1000);
    CHECK(between > 10000);
}

TEST_CASE("hs_float_of_signed_words rounds a 64-bit integer to float as the CPU's conversion does", "[gl][compute][fixed]") {
    std::mt19937_64 random(4302);
    std::vector<std::int64_t> values{0, 1, -1, std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min(),
                                     (std::int64_t(1) << 24) + 1, (std::int64_t(1) << 53) + 1, -(std::int64_t(1) << 40) - 3};
    for (int i = 0; i < 100000; ++i) {
        const std::uint64_t bits = random();
        const int width = int(random() % 64); // every magnitude, and ties: 25 significant bits, the last one set
        values.push_back(std::int64_t(bits >> (63 - width)) * (random() % 2 ? -1 : 1));
        values.push_back(std::int64_t(((bits >> 40) | 1u | 1u << 24) << (width % 39)) * (random() % 2 ? -1 : 1));
    }
    std::vector<std::uint32_t> words;
    for (std::int64_t v : values) words.push_back(std::uint32_t(std::uint64_t(v))), words.push_back(std::uint32_t(std::uint64_t(v) >> 32));
    const auto gpu = run_on_gpu(words, "result.x = floatBitsToUint(hs_float_of_signed_words(word))");
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < values.size(); ++i)
        if (gpu[2 * i] != test::bits_of(float(values[i])) && ++wrong <= 3)
            UNSCOPED_INFO(values[i] << ": CPU " << std::hexfloat << float(values[i]) << ", GPU " << test::from_bits(gpu[2 * i]));
    CHECK(wrong == 0);
}

TEST_CASE("hs_sqrt_rn gives std::sqrt's float bit for bit", "[gl][compute][fixed]") {
    std::mt19937 random(4303);
    std::vector<std::uint32_t> in;
    for (float x : test_floats(random, 200000)) in.push_back(test::bits_of(x)), in.push_back(0u);
    for (std::uint32_t bits = 0x3f800000u; bits < 0x40800000u; bits += 13) in.push_back(bits), in.push_back(0u); // [1, 4): both parities
    for (std::uint32_t bits = 1; bits < 0x00800000u; bits += 4099) in.push_back(bits), in.push_back(0u);          // subnormals
    for (std::uint32_t r = 1; r < 20000; ++r) { // perfect squares and the floats either side of them
        const float square = float(r) * float(r);
        for (float x : {square, std::nextafter(square, 0.0f), std::nextafter(square, 1e30f)}) in.push_back(test::bits_of(x)), in.push_back(0u);
    }
    const auto gpu = run_on_gpu(in, "result.x = floatBitsToUint(hs_sqrt_rn(uintBitsToFloat(word.x)))");
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < in.size(); i += 2) {
        const float x = test::from_bits(in[i]), expected = std::sqrt(x);
        const bool same = std::isnan(expected) ? gpu[i] == 0x7fc00000u : gpu[i] == test::bits_of(expected);
        if (!same && ++wrong <= 3) UNSCOPED_INFO(std::hexfloat << x << ": CPU " << expected << ", GPU " << test::from_bits(gpu[i]));
    }
    CHECK(wrong == 0);
}
