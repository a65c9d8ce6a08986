// shaders/arithmetic/exact_division.glsl in llvmpipe: hs_div_rn gives the CPU's float quotient bit for
// bit, and keeps giving it when the GPU's own division (its estimate) is made worse than GLSL allows.
#include <glad/gl.h>

#include <hairshadow/gl.hpp>

#include "gl_test_context.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace hairshadow;

namespace {

/// Runs hs_div_rn over `pairs` (bit patterns a0, b0, a1, b1, ...) with `native` as the estimate's
/// division; returns, per pair, the quotient's bits and the estimate's own quotient's bits.
std::vector<std::uint32_t> divide_on_gpu(const std::vector<std::uint32_t>& pairs, const std::string& native) {
    const std::string defines = native.empty() ? std::string() : "#define HS_NATIVE_DIVIDE(a, b) (" + native + ")\n";
    const std::string_view body = R"(
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= hs_count) return;
    float a = uintBitsToFloat(hs_in[2u * i]), b = uintBitsToFloat(hs_in[2u * i + 1u]);
    hs_out[2u * i] = floatBitsToUint(hs_div_rn(a, b));
    hs_out[2u * i + 1u] = floatBitsToUint(HS_NATIVE_DIVIDE(a, b));
}
)";
    return test::run_on_words(defines, {gl::shaders::arithmetic_exact_division}, body, pairs, std::uint32_t(pairs.size() / 2), "exact division test");
}

/// Operand pairs that reach every branch: special values against each other, random bit patterns
/// (any exponents), quotients near 1 (dense significands), near the overflow and subnormal
/// thresholds, and exact quotients and halfway cases built from small integers.
std::vector<std::uint32_t> test_pairs() {
    std::vector<float> special{0.0f, -0.0f, 1.0f, -1.0f, 3.0f, 0.1f, 7.0f, 1.5f, 2.0f, 0.5f,
                               std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::denorm_min(),
                               -std::numeric_limits<float>::denorm_min(), test::from_bits(0x007fffffu), test::from_bits(0x00400001u),
                               std::numeric_limits<float>::min(), std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
                               std::nextafter(1.0f, 2.0f), std::nextafter(1.0f, 0.0f), 16777215.0f, 16777216.0f, test::from_bits(0x3fffffffu)};
    std::vector<std::uint32_t> pairs;
    const auto add = [&](float a, float b) { pairs.push_back(test::bits_of(a)), pairs.push_back(test::bits_of(b)); };
    for (float a : special)
        for (float b : special) add(a, b);
    std::mt19937 random(43);
    std::uniform_int_distribution<std::uint32_t> any;
    std::uniform_int_distribution<std::uint32_t> significand(0, 0x7fffffu);
    const auto with_exponent = [&](int e, bool negative) {
        return test::from_bits((negative ? 0x80000000u : 0u) | (std::uint32_t(e) << 23) | significand(random));
    };
    for (int i = 0; i < 200000; ++i) {
        const float a = test::from_bits(any(random));
        add(a, test::from_bits(any(random)));
    }
    std::uniform_int_distribution<int> offset(-2, 2), sign(0, 1);
    // (Each operand drawn in its own statement: the pairs are the same whatever order a compiler
    // evaluates arguments in.)
    for (int i = 0; i < 200000; ++i) { // quotients in [1/4, 4]: every significand bit matters
        const int e = std::uniform_int_distribution<int>(3, 252)(random);
        const float a = with_exponent(e, sign(random) != 0);
        const int eb = e + offset(random);
        add(a, with_exponent(eb, sign(random) != 0));
    }
    for (int i = 0; i < 100000; ++i) {
        // Quotients near the largest float: biased exponents 254 and 255 before rounding.
        const int ea = std::uniform_int_distribution<int>(129, 254)(random);
        const float big = with_exponent(ea, false);
        const int eb = ea - 127 - std::uniform_int_distribution<int>(0, 1)(random);
        add(big, with_exponent(eb, sign(random) != 0));
        // Quotient exponents (biased) near and below 1: subnormal results.
        const int sub = std::uniform_int_distribution<int>(-30, 2)(random);
        const int e = std::uniform_int_distribution<int>(1, 127 + sub)(random), eb_sub = e - sub + 127; // in [126, 254]
        const float a_sub = with_exponent(e, sign(random) != 0);
        add(a_sub, with_exponent(eb_sub, false));
        const float subnormal = test::from_bits(significand(random));
        add(subnormal, with_exponent(std::uniform_int_distribution<int>(100, 130)(random), false)); // subnormal / normal
        const float small_normal = with_exponent(std::uniform_int_distribution<int>(1, 30)(random), false);
        add(small_normal, test::from_bits(significand(random) | 1u)); // small / subnormal
    }
    add(test::from_bits(0x007fffffu), test::from_bits(0x3f7ffffeu)); // rounds from the largest subnormal up to the smallest normal
    std::uniform_int_distribution<int> small(1, 1 << 24);
    for (int i = 0; i < 100000; ++i) { // exact quotients and ties: integers over powers of two and small integers
        const float n = float(small(random));
        const float d = float(std::uniform_int_distribution<int>(1, 64)(random));
        add(n, d);
        add(std::ldexp(n, -140), std::ldexp(d, 6)); // ties in the subnormals (d = 16, odd n)
    }
    return pairs;
}

/// Pairs whose GPU quotient differs from the CPU's a / b, NaN matching any NaN; prints the first few.
std::size_t mismatches(const std::vector<std::uint32_t>& pairs, const std::vector<std::uint32_t>& gpu, std::size_t slot) {
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < pairs.size(); i += 2) {
        const float expected = test::from_bits(pairs[i]) / test::from_bits(pairs[i + 1]);
        const std::uint32_t got = gpu[i + slot];
        const bool same = std::isnan(expected) ? std::isnan(test::from_bits(got)) : got == test::bits_of(expected);
        if (!same && ++wrong <= 3 && slot == 0)
            UNSCOPED_INFO("0x" << std::hex << pairs[i] << " / 0x" << pairs[i + 1] << ": CPU 0x" << test::bits_of(expected) << ", GPU 0x" << got);
    }
    return wrong;
}

} // namespace

TEST_CASE("hs_div_rn gives the CPU's float quotient bit for bit", "[gl][compute][division]") {
    const auto pairs = test_pairs();
    const auto gpu = divide_on_gpu(pairs, "");
    CHECK(mismatches(pairs, gpu, 0) == 0);
}

TEST_CASE("hs_div_rn does not depend on the GPU's division", "[gl][compute][division]") {
    // Estimates off by 8 to 16 ULP either way, and a division that truncates the last four bits: the
    // estimates themselves disagree with the CPU for most pairs (so the test can tell), the exact
    // quotient never does. (Only the truncating one reaches the correction for a negative remainder.)
    const auto pairs = test_pairs();
    for (const std::string native : {"(a) / (b) * 1.00000095", "(a) / (b) * 0.99999905",
                                     "uintBitsToFloat(floatBitsToUint((a) / (b)) & 0xfffffff0u)"}) {
        CAPTURE(native);
        const auto gpu = divide_on_gpu(pairs, native);
        CHECK(mismatches(pairs, gpu, 0) == 0);
        CHECK(mismatches(pairs, gpu, 1) > pairs.size() / 2 / 2); // most of the pairs (two words each)
    }
}

TEST_CASE("hs_div_rn by a compile-time constant gives the CPU's quotient", "[gl][compute][division]") {
    // Layer boundaries k / K divide by a constant the GLSL compiler may fold or strength-reduce.
    test::gl_context();
    for (int layers : {3, 7, 16, 64, 255, 256}) {
        CAPTURE(layers);
        const std::string defines = "#define HS_K " + std::to_string(layers) + "\n";
        const std::string_view body = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 1) writeonly buffer hs_out_block { uint hs_out[]; };
void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i > HS_K) return;
    hs_out[i] = floatBitsToUint(hs_div_rn(float(i), float(HS_K)));
}
)";
        const auto stage = gl::compile_stage(GL_COMPUTE_SHADER, defines, {gl::shaders::arithmetic_exact_division, body}, "constant division test");
        const auto program = gl::link_program({&stage}, "constant division test");
        auto out = gl::make_buffer();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.get());
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr((layers + 1) * 4), nullptr, GL_DYNAMIC_READ);
        glUseProgram(program.get());
        glDispatchCompute(GLuint(layers + 64) / 64, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<std::uint32_t> result(std::size_t(layers + 1));
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(result.size() * 4), result.data());
        glUseProgram(0);
        int wrong = 0;
        for (int i = 0; i <= layers; ++i)
            if (result[std::size_t(i)] != test::bits_of(float(i) / float(layers)) && ++wrong <= 3)
                UNSCOPED_INFO(i << " / " << layers << ": CPU " << float(i) / float(layers) << ", GPU " << test::from_bits(result[std::size_t(i)]));
        CHECK(wrong == 0);
    }
}
