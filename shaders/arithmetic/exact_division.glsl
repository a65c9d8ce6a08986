// A float quotient every GPU rounds the same, from 32-bit integers: hs_div_rn(a, b) is the IEEE 754
// binary32 quotient rounded to nearest even, which is the CPU's a / b, for all a and b (zeros,
// subnormals and infinities included, as bit patterns: a GPU that flushes subnormals may flush one
// on its way in or out). NaN, 0/0 and inf/inf give the quiet NaN 0x7fc00000, whose sign and payload
// may differ from the CPU's. GLSL lets a float division be
// 2.5 ULP off (ARB_shader_precision, core since GL 4.1) and leaves double precision unspecified, so a
// quotient that must give the CPU's bits cannot come from either. The GPU's own division only
// estimates the quotient's 26 leading bits; an exact remainder, kept in 32-bit words that wrap,
// corrects the estimate for any GPU error up to 16 ULP (the remainder must stay below 2^31).
// Every program that divides where the bits matter composes this first; the guard lets two snippets
// that need it sit in one program.
#ifndef HS_EXACT_DIVISION
#define HS_EXACT_DIVISION

#ifndef HS_NATIVE_DIVIDE // the estimate: tests define a deliberately worse one
#define HS_NATIVE_DIVIDE(a, b) ((a) / (b))
#endif

// The significand m in [2^23, 2^24) and biased exponent e of a finite non-zero float of magnitude bits
// `x`: |value| = m 2^(e - 150); a subnormal is normalised (e below 1).
void hs_unpack_float(uint x, out uint m, out int e) {
    e = int(x >> 23);
    m = x & 0x7fffffu;
    if (e == 0) {
        int shift = 23 - findMSB(m);
        m <<= uint(shift);
        e = 1 - shift;
    } else {
        m |= 0x800000u;
    }
}

float hs_div_rn(float a, float b) {
    uint ua = floatBitsToUint(a), ub = floatBitsToUint(b);
    uint sign = (ua ^ ub) & 0x80000000u;
    uint xa = ua & 0x7fffffffu, xb = ub & 0x7fffffffu;
    const uint inf = 0x7f800000u;
    if (xa > inf || xb > inf || (xa == xb && (xa == 0u || xa == inf))) return uintBitsToFloat(0x7fc00000u);
    if (xa == inf || xb == 0u) return uintBitsToFloat(sign | inf);
    if (xa == 0u || xb == inf) return uintBitsToFloat(sign);
    uint ma, mb;
    int ea, eb;
    hs_unpack_float(xa, ma, ea);
    hs_unpack_float(xb, mb, eb);
    int e = ea - eb + 127; // the quotient's biased exponent, once ma / mb is in [1, 2)
    if (ma < mb) {
        ma <<= 1u;
        --e;
    }
    if (e >= 255) return uintBitsToFloat(sign | inf);
    // q = floor(ma 2^25 / mb) in [2^25, 2^26) and r = ma 2^25 - q mb in [0, mb). The estimate is
    // within 11 of q for a division within 2.5 ULP (within 65 for one within 16 ULP); r, exact
    // modulo 2^32, is then below 2^31 in size, so the wrapped words hold it exactly. r / mb, below 128
    // in size, is estimated to well within 1, so its floor is off by at most one, which one
    // correction each way mends. No loops: with loops correcting one step at a time, llvmpipe's
    // 256-layer compute pass left the later layers of some texels zero (not understood; this form
    // passes), and a GPU pays for their divergence.
    uint q = uint(HS_NATIVE_DIVIDE(float(ma), float(mb)) * 33554432.0);
    int r = int((ma << 25u) - q * mb);
    int d = int(floor(HS_NATIVE_DIVIDE(float(r), float(mb))));
    r -= d * int(mb);
    q += uint(d);
    if (r < 0) {
        r += int(mb);
        --q;
    }
    if (r >= int(mb)) {
        r -= int(mb);
        ++q;
    }
    // Keep 24 bits of q for a normal result, fewer for a subnormal one (its unit is 2^-149), and round
    // to nearest even on the bits shifted out and the remainder.
    int shift = max(2, 3 - e);
    if (shift > 26) return uintBitsToFloat(sign); // below half the smallest subnormal
    uint m = q >> uint(shift);
    uint half_bit = (q >> uint(shift - 1)) & 1u;
    bool sticky = r != 0 || (q & ((1u << uint(shift - 1)) - 1u)) != 0u;
    m += half_bit & uint(sticky || (m & 1u) != 0u);
    // The significand's leading bit adds one to the exponent field, and a carry out of it (from the
    // largest subnormal to the smallest normal; a normal quotient's significand stays below
    // 2 - 2^-24, so it never carries) another. The min only guards.
    uint bits = (uint(max(e - 1, 0)) << 23) + m;
    return uintBitsToFloat(sign | min(bits, inf));
}

#endif
