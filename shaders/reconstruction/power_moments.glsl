// Moment shadow maps for translucent occluders (Peters et al. 2016; Münstermann et al. 2018), mirroring
// hairshadow::power_moments<HS_MOMENTS> and reconstruction/detail/polynomial_roots.hpp: a fragment of
// optical depth b at z = 2 s - 1 adds b, b z, .. b z^HS_MOMENTS; a query at z normalises the moments by
// b_0, pulls the even ones by hs_moment_pull (the CPU's bias times MBOIT's bias vector), and takes b_0
// times the share of the canonical distribution in front of z (z and the roots of a polynomial of
// degree HS_MOMENTS / 2), its point at z weighted by hs_moment_overestimation. Float, in the CPU's
// order of operations.
#define HS_SUMS (HS_MOMENTS + 1)
#define HS_MOMENT_POINTS (HS_MOMENTS / 2)
uniform float hs_moment_overestimation;
uniform float hs_moment_bias;
uniform float hs_moment_pull[HS_MOMENT_POINTS];

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

#if HS_MOMENT_POINTS > 2
// The roots of a polynomial whose roots are all real (degree 3 or 4), as polynomial_roots.hpp finds
// them: each between two roots of the derivative, the outer ones bracketed by doubling a step outward,
// then 40 halvings.
float hs_polynomial_at(float c[HS_MOMENT_POINTS + 1], int degree, float z) {
    precise float value = c[degree];
    for (int k = degree - 1; k >= 0; --k) value = value * z + c[k];
    return value;
}

float hs_bisected_root(float c[HS_MOMENT_POINTS + 1], int degree, float lo, float hi) {
    float at_lo = hs_polynomial_at(c, degree, lo), at_hi = hs_polynomial_at(c, degree, hi);
    bool negative_at_lo = at_lo < 0.0;
    if ((at_hi < 0.0) == negative_at_lo) return abs(at_lo) <= abs(at_hi) ? lo : hi; // a double root, as on the CPU
    for (int step = 0; step < 40; ++step) {
        precise float mid = 0.5 * (lo + hi);
        if ((hs_polynomial_at(c, degree, mid) < 0.0) == negative_at_lo) lo = mid;
        else hi = mid;
    }
    precise float root = 0.5 * (lo + hi);
    return root;
}

// The roots of the polynomial c of `degree` (3 or 4), ascending, given its derivative's.
void hs_isolated_roots(float c[HS_MOMENT_POINTS + 1], int degree, float critical[HS_MOMENT_POINTS], out float roots[HS_MOMENT_POINTS]) {
    for (int i = 0; i < degree; ++i) {
        precise float lo, hi;
        if (i == 0 || i == degree - 1) {
            float from = i == 0 ? critical[0] : critical[degree - 2], direction = i == 0 ? -1.0 : 1.0;
            bool negative_at_from = hs_polynomial_at(c, degree, from) < 0.0;
            precise float step = 1.0, to = from + direction * step;
            for (int k = 0; k < 60 && (hs_polynomial_at(c, degree, to) < 0.0) == negative_at_from; ++k) {
                step = 2.0 * step;
                to = from + direction * step;
            }
            if ((hs_polynomial_at(c, degree, to) < 0.0) == negative_at_from) {
                roots[i] = from; // no change of sign: a double root at the critical point
                continue;
            }
            lo = i == 0 ? to : from;
            hi = i == 0 ? from : to;
        } else {
            lo = critical[i - 1];
            hi = critical[i];
        }
        roots[i] = hs_bisected_root(c, degree, lo, hi);
    }
}

// The stable quadratic formula's two roots of c[0] + c[1] z + c[2] z^2, ascending.
void hs_quadratic_roots(float c[HS_MOMENT_POINTS + 1], out float roots[HS_MOMENT_POINTS]) {
    precise float middle = 0.5 * c[1];
    precise float root = sqrt(max(middle * middle - c[0] * c[2], 0.0));
    precise float t = -(middle + (middle < 0.0 ? -root : root));
    precise float z1 = t / c[2], z2 = c[0] / t;
    roots[0] = min(z1, z2);
    roots[1] = max(z1, z2);
}

void hs_moment_roots(float c[HS_MOMENT_POINTS + 1], out float roots[HS_MOMENT_POINTS]) {
    float slope[HS_MOMENT_POINTS + 1], critical[HS_MOMENT_POINTS];
    for (int k = 0; k < HS_MOMENT_POINTS; ++k) {
        precise float s = float(k + 1) * c[k + 1];
        slope[k] = s;
    }
    slope[HS_MOMENT_POINTS] = 0.0;
#if HS_MOMENT_POINTS == 3
    hs_quadratic_roots(slope, critical);
#else
    float second[HS_MOMENT_POINTS + 1], inflexion[HS_MOMENT_POINTS];
    for (int k = 0; k < 3; ++k) {
        precise float s = float(k + 1) * slope[k + 1];
        second[k] = s;
    }
    second[3] = 0.0;
    second[4] = 0.0;
    hs_quadratic_roots(second, inflexion);
    hs_isolated_roots(slope, 3, inflexion, critical);
#endif
    hs_isolated_roots(c, HS_MOMENT_POINTS, critical, roots);
}
#endif

float hs_series_optical_depth(float sums[HS_SUMS], float s) {
    const int n = HS_MOMENT_POINTS;
    // The biased normalised moments, b[0] = 1.
    float b[HS_SUMS];
    precise float b0 = sums[0], keep = 1.0 - hs_moment_bias;
    b[0] = 1.0;
    for (int j = 1; j <= HS_MOMENTS; ++j) {
        precise float bj = keep * (sums[j] / b0);
        if (j % 2 == 0) bj = bj + hs_moment_pull[j / 2 - 1];
        b[j] = bj;
    }
    precise float z0 = 2.0 * s - 1.0;
    // LDL^T of the Hankel matrix H_ij = b_(i+j) (e = l d).
    float l[(n + 1) * (n + 1)], e[(n + 1) * (n + 1)], d[n + 1];
    for (int k = 0; k < (n + 1) * (n + 1); ++k) l[k] = e[k] = 0.0;
    d[0] = 1.0;
    for (int i = 1; i <= n; ++i) l[i * (n + 1)] = e[i * (n + 1)] = b[i];
    for (int j = 1; j <= n; ++j) {
        precise float djj = b[2 * j];
        for (int k = 0; k < j; ++k) djj = djj - e[j * (n + 1) + k] * l[j * (n + 1) + k];
        d[j] = djj;
        for (int i = j + 1; i <= n; ++i) {
            precise float eij = b[i + j];
            for (int k = 0; k < j; ++k) eij = eij - e[i * (n + 1) + k] * l[j * (n + 1) + k];
            precise float lij = eij / djj;
            e[i * (n + 1) + j] = eij;
            l[i * (n + 1) + j] = lij;
        }
    }
    // c = H^-1 (1, z0, .. z0^n).
    float c[n + 1];
    c[0] = 1.0;
    precise float power = 1.0;
    for (int i = 1; i <= n; ++i) {
        power = power * z0;
        precise float ci = power;
        for (int k = 0; k < i; ++k) ci = ci - l[i * (n + 1) + k] * c[k];
        c[i] = ci;
    }
    for (int i = 1; i <= n; ++i) {
        precise float ci = c[i] / d[i];
        c[i] = ci;
    }
    for (int i = n - 1; i >= 0; --i) {
        precise float sum = l[(i + 1) * (n + 1) + i] * c[i + 1];
        for (int j = i + 2; j <= n; ++j) sum = sum + l[j * (n + 1) + i] * c[j];
        precise float ci = c[i] - sum;
        c[i] = ci;
    }
    // The support points and their weights.
    float z[n + 1], f[n + 1], roots[n];
#if HS_MOMENT_POINTS == 2
    precise float p = c[1] / c[2], q = c[0] / c[2];
    precise float r = sqrt(0.25 * p * p - q);
    precise float r1 = -0.5 * p - r, r2 = -0.5 * p + r;
    roots[0] = r1;
    roots[1] = r2;
#else
    hs_moment_roots(c, roots);
#endif
    z[0] = z0;
    f[0] = hs_moment_overestimation;
    for (int i = 1; i <= n; ++i) {
        z[i] = roots[i - 1];
        f[i] = z[i] < z0 ? 1.0 : 0.0;
    }
    // The polynomial interpolating the weights (divided differences, then monomial coefficients).
    for (int order = 1; order <= n; ++order)
        for (int i = n; i >= order; --i) {
            precise float fi = (f[i] - f[i - 1]) / (z[i] - z[i - order]);
            f[i] = fi;
        }
    float qc[n + 1];
    for (int k = 0; k <= n; ++k) qc[k] = 0.0;
    qc[0] = f[n];
    for (int k = n - 1, degree = 0; k >= 0; --k, ++degree) {
        qc[degree + 1] = qc[degree];
        for (int i = degree; i >= 1; --i) {
            precise float qi = qc[i - 1] - qc[i] * z[k];
            qc[i] = qi;
        }
        precise float q0 = f[k] - qc[0] * z[k];
        qc[0] = q0;
    }
    precise float share = qc[0];
    for (int k = 1; k <= n; ++k) share = share + b[k] * qc[k];
    return b0 * (isnan(share) || isinf(share) ? hs_moment_overestimation : share); // no solution: the query's own weight, as on the CPU
}
