// What Fourier opacity maps and moment shadow maps share (mirrors
// reconstruction/detail/depth_projection.hpp), composed after the reconstruction's snippet: a
// fragment's place in its texel's depth range, 0 at the nearest fragment and 1 at the furthest,
// divided as the CPU divides (hs_div_rn); the terms a fragment adds and the sums a texel stores, under either accumulation.
float hs_position_in_range(float nearest, float furthest, float depth) {
    precise float span = furthest - nearest;
    precise float offset = depth - nearest;
    return span > 0.0 ? clamp(hs_div_rn(offset, span), 0.0, 1.0) : 0.0;
}

// The terms a fragment adds (composed after the reconstruction, whose hs_projection_terms and HS_SUMS
// it uses): the reconstruction's, or with an 8-bit accumulation (HS_EIGHT_BIT) their non-negative
// encoding, (t_0 + t_k) / (2 c) and t_0 / c with c = HS_TERMS_PER_OPTICAL_DEPTH, as the CPU encodes them.
void hs_added_terms(float s, float b, out float terms[HS_SUMS]) {
    hs_projection_terms(s, b, terms);
#ifdef HS_EIGHT_BIT
    float t0 = terms[0];
    for (int k = 1; k < HS_SUMS; ++k) {
        precise float step = (t0 + terms[k]) * (0.5 / HS_TERMS_PER_OPTICAL_DEPTH);
        terms[k] = step;
    }
    terms[0] = t0 * (1.0 / HS_TERMS_PER_OPTICAL_DEPTH);
#endif
}

// A texel's signed sums from what it stores (the accumulation's hs_decode of each): with 8-bit steps,
// t_0 = c B and t_k = c (2 b_k - B), B the decoded step sum of term 0.
void hs_decode_sums(inout float sums[HS_SUMS]) {
#ifdef HS_EIGHT_BIT
    float total = hs_decode(sums[0]);
    sums[0] = HS_TERMS_PER_OPTICAL_DEPTH * total;
    for (int k = 1; k < HS_SUMS; ++k) {
        precise float t = HS_TERMS_PER_OPTICAL_DEPTH * (2.0 * hs_decode(sums[k]) - total);
        sums[k] = t;
    }
#endif
}
