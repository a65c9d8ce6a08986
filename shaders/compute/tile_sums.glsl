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
// Adds a 64-bit integer (two's complement, so negative terms too) to a slot.
void hs_add_fixed(uint slot, int64_t value) {
    uint64_t q = uint64_t(value);
    uint low = uint(q & 0xffffffffUL), high = uint(q >> 32);
    uint before = atomicAdd(hs_sum_low[slot], low);
    if (before + low < before) ++high; // the low word carried
    if (high != 0u) atomicAdd(hs_sum_high[slot], high);
}
#endif

void hs_add_sum(uint slot, float b) {
#ifdef HS_EIGHT_BIT
    atomicAdd(hs_sum_low[slot], hs_eight_bit_step(b));
#else
    hs_add_fixed(slot, int64_t(b * 1099511627776.0)); // b 2^40: exact for b >= 2^-16
#endif
}

// A slot's sum: 2^40 times the optical depth, or the 8-bit steps (unsaturated).
uint64_t hs_sum(uint slot) {
#ifndef HS_WIDE_SUMS
    return uint64_t(hs_sum_low[slot]);
#else
    return (uint64_t(hs_sum_high[slot]) << 32) | uint64_t(hs_sum_low[slot]);
#endif
}
// a + b as the accumulation combines them (the 8-bit sum saturates).
uint64_t hs_combine(uint64_t a, uint64_t b) {
#ifdef HS_EIGHT_BIT
    return a + b < 255UL ? a + b : 255UL;
#else
    return a + b;
#endif
}
// The value a texture stores for a sum: the optical depth, or the 8-bit level over 255.
float hs_stored(uint64_t sum) {
#ifdef HS_EIGHT_BIT
    return float(sum < 255UL ? sum : 255UL) / 255.0;
#else
    return float(double(sum) / 1099511627776.0lf);
#endif
}
