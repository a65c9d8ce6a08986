// A float square root every GPU rounds the same, from 32-bit integers: hs_sqrt_rn(x) is the IEEE 754
// binary32 square root rounded to nearest even, which is the CPU's std::sqrt(float), for x >= 0
// (subnormals and +inf included, -0 gives -0); a negative x or NaN gives the quiet NaN 0x7fc00000.
// GLSL's sqrt may be off by more than an ULP (ARB_shader_precision: it inherits inversesqrt's 2 ULP),
// so a root that must give the CPU's bits cannot come from it. Composed after
// arithmetic/exact_division, whose hs_unpack_float it uses.
#ifndef HS_EXACT_SQUARE_ROOT
#define HS_EXACT_SQUARE_ROOT
#ifndef HS_EXACT_DIVISION
#error "arithmetic/exact_square_root needs arithmetic/exact_division before it"
#endif

float hs_sqrt_rn(float x) {
    uint u = floatBitsToUint(x);
    if ((u & 0x7fffffffu) == 0u || u == 0x7f800000u) return x; // +-0 and +inf are their own roots
    if (u > 0x7f800000u) return uintBitsToFloat(0x7fc00000u);  // negative, or NaN
    uint m;
    int e;
    hs_unpack_float(u, m, e); // x = m 2^(e - 150), m in [2^23, 2^24)
    // x = M 2^(2k) with M = m 2^23 or m 2^24, in [2^46, 2^48), so that sqrt(M) is in [2^23, 2^24):
    // its integer part r is the root's significand before rounding.
    int p = e - 173; // x = (m 2^23) 2^p
    bool odd = (p & 1) != 0;
    uvec2 big = odd ? uvec2(m << 24, m >> 8) : uvec2(m << 23, m >> 9); // M as (low, high) words
    int k = odd ? (p - 1) / 2 : p / 2;
    // r = floor(sqrt(M)) bit by bit: a bit stays where the square does not pass M (squares below
    // 2^48: umulExtended keeps them exactly).
    uint r = 0u;
    for (int bit = 23; bit >= 0; --bit) {
        uint c = r | (1u << uint(bit)), high, low;
        umulExtended(c, c, high, low);
        if (high < big.y || (high == big.y && low <= big.x)) r = c;
    }
    // Round to nearest: up where sqrt(M) >= r + 1/2, that is M - r^2 >= r + 1/4, so M - r^2 > r (a
    // tie cannot happen). M - r^2 <= 2r is below 2^25, so the low words' wrapped difference is exact.
    uint high, low;
    umulExtended(r, r, high, low);
    if (big.x - low > r) ++r; // r = 2^24 stays exact in float
    return ldexp(float(r), k); // a normal float: the root of any positive float is
}

#endif
