// Moment shadow maps for translucent occluders (Peters et al. 2016; Münstermann et al. 2018), mirroring
// hairshadow::power_moments: a fragment of optical depth b at z = 2 s - 1 adds b, b z, b z^2, b z^3 and
// b z^4; a query at z normalises the moments by b_0, pulls them toward (0, 0.375, 0, 0.375) by
// hs_moment_bias, and takes b_0 times the share of the canonical distribution (Hamburger 4MSM) in front
// of z, its point at z weighted by hs_moment_overestimation. Float, in the CPU's order of operations.
#define HS_SUMS (HS_MOMENTS + 1)
uniform float hs_moment_overestimation;
uniform float hs_moment_bias;

void hs_projection_terms(float s, float b, out float terms[HS_SUMS]) {
    precise float z = 2.0 * s - 1.0;
    precise float power = b;
    terms[0] = b;
    for (int j = 1; j <= HS_MOMENTS; ++j) {
        power = power * z;
        terms[j] = power;
    }
}

float hs_total_optical_depth(float sums[HS_SUMS]) { return sums[0]; }

float hs_series_optical_depth(float sums[HS_SUMS], float s) {
    precise float b0 = sums[0], keep = 1.0 - hs_moment_bias, pull = hs_moment_bias * 0.375;
    precise float b1 = keep * (sums[1] / b0), b2 = keep * (sums[2] / b0) + pull;
    precise float b3 = keep * (sums[3] / b0), b4 = keep * (sums[4] / b0) + pull;
    precise float z0 = 2.0 * s - 1.0;
    precise float d11 = b2 - b1 * b1;
    precise float l21d11 = b3 - b1 * b2;
    precise float l21 = l21d11 / d11;
    precise float d22 = (b4 - b2 * b2) - l21d11 * l21;
    precise float c1 = z0 - b1;
    precise float c2 = z0 * z0 - b2 - l21 * c1;
    c1 = c1 / d11;
    c2 = c2 / d22;
    c1 = c1 - l21 * c2;
    precise float c0 = 1.0 - (c1 * b1 + c2 * b2);
    precise float p = c1 / c2, q = c0 / c2;
    precise float r = sqrt(0.25 * p * p - q);
    precise float z1 = -0.5 * p - r, z2 = -0.5 * p + r;
    float f0 = hs_moment_overestimation, f1 = z1 < z0 ? 1.0 : 0.0, f2 = z2 < z0 ? 1.0 : 0.0;
    precise float f01 = (f1 - f0) / (z1 - z0), f12 = (f2 - f1) / (z2 - z1), f012 = (f12 - f01) / (z2 - z0);
    precise float q2 = f012, q1 = (f01 - f012 * z1) - q2 * z0;
    precise float q0 = f0 - (f01 - f012 * z1) * z0;
    precise float share = q0 + b1 * q1 + b2 * q2;
    return b0 * (isnan(share) || isinf(share) ? f0 : share); // no solution: the query's own weight, as on the CPU
}
