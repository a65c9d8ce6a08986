// Sums that do not depend on the order of their terms, for the compute build's accumulation passes
// (one work group per tile): float optical depths in 64-bit fixed point (2^-40), kept as two 32-bit
// words with the carry passed by hand, or emulated 8-bit steps (HS_EIGHT_BIT) summed as integers and
// saturated once, which equals saturating after every add because every step is non-negative.
// HS_SUM_SLOTS slots per texel of the tile (of HS_SUM_TEXELS texels, 256 unless set). HS_FIXED_SUMS
// keeps 64-bit integer slots (hs_add_fixed) beside 8-bit steps.
#ifndef HS_SUM_TEXELS
#define HS_SUM_TEXELS 256
#endif
#if !defined(HS_EIGHT_BIT) || defined(HS_FIXED_SUMS)
#define HS_WIDE_SUMS
#endif
shared uint hs_sum_low[HS_SUM_TEXELS * HS_SUM_SLOTS];
#ifdef HS_WIDE_SUMS
shared uint hs_sum_high[HS_SUM_TEXELS * HS_SUM_SLOTS];
#endif

void hs_clear_sums() {
    for (uint i = gl_LocalInvocationIndex; i < uint(HS_SUM_TEXELS * HS_SUM_SLOTS); i += 256u) {
        hs_sum_low[i] = 0u;
#ifdef HS_WIDE_SUMS
        hs_sum_high[i] = 0u;
#endif
    }
}

#ifdef HS_EIGHT_BIT
// The 8-bit step of optical depth b: its output b / kappa in unorm8, rounded half away from zero.
uint hs_eight_bit_step(float b) {
    precise float x = clamp(hs_div_rn(b, HS_KAPPA), 0.0, 1.0) * 255.0;
    return uint(x) + (fract(x) >= 0.5 ? 1u : 0u);
}
#endif

#ifdef HS_WIDE_SUMS
// Adds a 64-bit integer, two's complement (so negative terms too) as (low word, high word), to a slot.
void hs_add_fixed(uint slot, uvec2 value) {
    uint before = atomicAdd(hs_sum_low[slot], value.x);
    uint high = value.y + (before + value.x < before ? 1u : 0u); // the low word carried
    if (high != 0u) atomicAdd(hs_sum_high[slot], high);
}
#endif

// trunc(x 2^40) for |x| below 2^23 as (low, high) words, two's complement: int64_t(x * 2^40) on the
// CPU (the projected methods' terms may be negative). The scaling by powers of two, the floor and the
// difference are exact in float; uint() truncates the fraction; a negative x negates the magnitude's.
uvec2 hs_fixed_words(float x) {
    precise float scaled = abs(x) * 1099511627776.0;
    precise float high = floor(scaled * (1.0 / 4294967296.0));
    precise float low = scaled - high * 4294967296.0;
    uvec2 magnitude = uvec2(uint(low), uint(high));
    return x >= 0.0 ? magnitude : hs_negated_words(magnitude);
}

void hs_add_sum(uint slot, float b) {
#ifdef HS_EIGHT_BIT
    atomicAdd(hs_sum_low[slot], hs_eight_bit_step(b));
#else
    hs_add_fixed(slot, hs_fixed_words(b)); // b 2^40: exact for b >= 2^-16
#endif
}

// A slot's sum as (low, high) words: 2^40 times the optical depth, or the 8-bit steps (unsaturated).
uvec2 hs_sum(uint slot) {
#ifndef HS_WIDE_SUMS
    return uvec2(hs_sum_low[slot], 0u);
#else
    return uvec2(hs_sum_low[slot], hs_sum_high[slot]);
#endif
}
// a + b as the accumulation combines them (the 8-bit sum saturates).
uvec2 hs_combine(uvec2 a, uvec2 b) {
#ifdef HS_EIGHT_BIT
    return uvec2(min(a.x + b.x, 255u), 0u); // a at most 255, b a slot's step sum: far below 2^32
#else
    uint low = a.x + b.x;
    return uvec2(low, a.y + b.y + (low < a.x ? 1u : 0u));
#endif
}
// The value a texture stores for a sum: the optical depth, or the 8-bit level over 255.
float hs_stored(uvec2 sum) {
#ifdef HS_EIGHT_BIT
    return float(min(sum.x, 255u)) / 255.0;
#else
    return hs_float_of_words(sum) * (1.0 / 1099511627776.0); // a power of two: exact
#endif
}
// The same for a signed sum (two's complement), whose terms may be negative.
float hs_stored_signed(uvec2 sum) {
    if ((sum.y & 0x80000000u) == 0u) return hs_stored(sum);
    return -hs_stored(hs_negated_words(sum)); // the magnitude, as x >= 0 has it
}
