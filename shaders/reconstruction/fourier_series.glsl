// Fourier opacity maps (Jansen & Bavoil 2010), mirroring hairshadow::fourier_series: a fragment of
// optical depth b at position s of its texel's range is a spike at t = m + (1 - 2m) s of the period,
// adding 2b, 2b cos(2 pi k t) and 2b sin(2 pi k t) (k = 1 .. HS_HARMONICS) to the coefficients; the
// optical depth in front of t integrates the series, each harmonic weighted by hs_fourier_weight[k]
// (its sigma factor, 1 undamped, over 2 pi k, as the CPU rounded it). Harmonics by the angle-sum
// recurrence.
#define HS_SUMS (2 * HS_HARMONICS + 1)
uniform float hs_fourier_weight[HS_HARMONICS + 1];
uniform float hs_fourier_margin; // where the texel's range starts in the period: 1/C, damped 1/C + 1/(C + 1)
uniform float hs_fourier_span;   // 1 - 2 margin

float hs_fourier_position(float s) {
    precise float t = hs_fourier_margin + hs_fourier_span * s;
    return t;
}

void hs_projection_terms(float s, float b, out float terms[HS_SUMS]) {
    float angle = 6.2831855 * hs_fourier_position(s);
    float c1 = cos(angle), s1 = sin(angle);
    precise float a0 = 2.0 * b;
    terms[0] = a0;
    precise float ck = c1, sk = s1;
    for (int k = 1; k <= HS_HARMONICS; ++k) {
        terms[2 * k - 1] = a0 * ck;
        terms[2 * k] = a0 * sk;
        precise float c = ck * c1 - sk * s1, s2 = sk * c1 + ck * s1;
        ck = c;
        sk = s2;
    }
}

float hs_total_optical_depth(float sums[HS_SUMS]) { return 0.5 * sums[0]; }

float hs_series_optical_depth(float sums[HS_SUMS], float s) {
    precise float t = hs_fourier_position(s);
    float angle = 6.2831855 * t;
    float c1 = cos(angle), s1 = sin(angle);
    precise float tau = 0.5 * sums[0] * t;
    precise float ck = c1, sk = s1;
    for (int k = 1; k <= HS_HARMONICS; ++k) {
        tau += hs_fourier_weight[k] * (sums[2 * k - 1] * sk + sums[2 * k] * (1.0 - ck));
        precise float c = ck * c1 - sk * s1, s2 = sk * c1 + ck * s1;
        ck = c;
        sk = s2;
    }
    return tau;
}
