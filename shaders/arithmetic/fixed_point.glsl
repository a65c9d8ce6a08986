// 64-bit integers as two 32-bit words (low, high), two's complement where signed, for programs that
// must give the CPU's bits with no 64-bit integers or double precision (GL 4.3 core has neither): the
// compute path's fixed-point sums and density clustering's k-means terms. Composed after
// arithmetic/exact_division, whose hs_unpack_float it uses.
#ifndef HS_FIXED_POINT
#define HS_FIXED_POINT
#ifndef HS_EXACT_DIVISION
#error "arithmetic/fixed_point needs arithmetic/exact_division before it"
#endif

// -v for a 64-bit integer (low, high) in two's complement.
uvec2 hs_negated_words(uvec2 v) { return uvec2(~v.x + 1u, ~v.y + (v.x == 0u ? 1u : 0u)); }

// An unsigned 64-bit integer (low, high) as a float, rounded to nearest even once, as the CPU's
// float(v) is (and float(double(v)) for v below 2^53, which a double holds exactly): its top 32
// bits, with a sticky bit for any bit below them, convert correctly rounded (GLSL's uint-to-float
// conversion), then scale.
float hs_float_of_words(uvec2 v) {
    if (v.y == 0u) return float(v.x);
    int shift = 31 - findMSB(v.y); // leading zeros of the high word
    uint top = shift == 0 ? v.y : (v.y << shift) | (v.x >> (32 - shift));
    uint below = v.x << shift; // shift < 32
    return ldexp(float(top | (below != 0u ? 1u : 0u)), 32 - shift);
}
// A signed 64-bit integer (two's complement) as a float, rounded to nearest even once: float(v) on
// the CPU. The magnitude rounds as hs_float_of_words does, and rounding is symmetric.
float hs_float_of_signed_words(uvec2 v) {
    if ((v.y & 0x80000000u) == 0u) return hs_float_of_words(v);
    return -hs_float_of_words(hs_negated_words(v)); // -2^63's magnitude, 2^63, is right as unsigned
}

// trunc(a b 2^36) as (low, high) words, two's complement: density clustering's k-means term,
// clustered::fixed_sum of the product of two floats on the CPU (exact there in double). The
// significands' product is exact in 48 bits (umulExtended), and shifting it by the exponents
// truncates toward zero; 2^63 units or more saturate at 2^63 - 1 in size, and NaN (0 times infinity
// too) gives 0, as fixed_sum does.
uvec2 hs_fixed_product(float a, float b) {
    uint ua = floatBitsToUint(a), ub = floatBitsToUint(b);
    uint xa = ua & 0x7fffffffu, xb = ub & 0x7fffffffu;
    const uint inf = 0x7f800000u;
    if (xa > inf || xb > inf || xa == 0u || xb == 0u) return uvec2(0u);
    const uvec2 most = uvec2(0xffffffffu, 0x7fffffffu);
    uvec2 magnitude = most;
    if (xa != inf && xb != inf) {
        uint ma, mb, high, low;
        int ea, eb;
        hs_unpack_float(xa, ma, ea);
        hs_unpack_float(xb, mb, eb);
        umulExtended(ma, mb, high, low); // in [2^46, 2^48)
        int shift = ea + eb - 264;       // a b 2^36 = (ma mb) 2^shift
        int top = high >= 0x8000u ? 47 : 46; // the product's leading bit
        if (top + shift >= 63) magnitude = most;
        else if (shift >= 0) magnitude = uvec2(low << uint(shift), shift == 0 ? high : (high << uint(shift)) | (low >> uint(32 - shift)));
        else if (shift <= -48) magnitude = uvec2(0u);
        else if (shift > -32) magnitude = uvec2((low >> uint(-shift)) | (high << uint(32 + shift)), high >> uint(-shift));
        else magnitude = uvec2(high >> uint(-shift - 32), 0u);
    }
    return ((ua ^ ub) & 0x80000000u) != 0u ? hs_negated_words(magnitude) : magnitude;
}

#endif
