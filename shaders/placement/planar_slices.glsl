// Opacity shadow maps' planar slices (Kim & Neumann 2001, section 2): HS_LAYERS maps between D_0 (the
// nearest fragment of the whole map) and D_N (just beyond the furthest); uniform spacing, or
// D_i = D_0 + (D_N - D_0)(i/N)^2 when HS_GAMMA_SPACING is defined. Mirrors planar_slices, whose
// prepare() takes D_0 and D_N from the map's extent as hs_slices(hs_map_extent()) does.
vec2 hs_slices(vec2 extent) { return vec2(extent.x, hs_just_above(extent.y)); }

float hs_spacing(float t) {
#ifdef HS_GAMMA_SPACING
    return t * t;
#else
    return t;
#endif
}
float hs_spacing_inverse(float u) {
#ifdef HS_GAMMA_SPACING
    return sqrt(u);
#else
    return u;
#endif
}

// i / N for i in [0, N], as the CPU rounds it: its table (planar_slices::fractions) as bits.
#ifdef HS_SLICE_FRACTION_BITS
const uint hs_slice_fraction_bits[HS_LAYERS + 1] = HS_SLICE_FRACTION_BITS;
float hs_slice_fraction(int i) { return uintBitsToFloat(hs_slice_fraction_bits[i]); }
#else
float hs_slice_fraction(int i) { return hs_div_rn(float(i), float(HS_LAYERS)); }
#endif

// D_i, for slices = (D_0, D_N).
float hs_boundary(int i, vec2 slices) {
    precise float value = i >= HS_LAYERS ? slices.y : slices.x + (slices.y - slices.x) * hs_spacing(hs_slice_fraction(min(i, HS_LAYERS)));
    return value;
}

hs_layer_position hs_locate(float depth) {
    vec2 extent = hs_map_extent(); // one fetch per call
    vec2 s = hs_slices(extent);
    if (!(depth >= s.x)) return hs_layer_position(-1, 0.0);
    // depth >= D_N, D_N being just above the furthest fragment (a denormal, which GLSL may flush, above 0)
    if (depth > extent.y) return hs_layer_position(HS_LAYERS, 0.0);
    int k = hs_estimate_index(hs_spacing_inverse((depth - s.x) / (s.y - s.x)) * float(HS_LAYERS), HS_LAYERS - 1);
    // The estimate settled by exact comparisons, carrying the boundaries it compared with so that
    // each is worked out once (an hs_div_rn where the placement gave no table).
    float lo = hs_boundary(k, s);
    while (k > 0 && depth < lo) lo = hs_boundary(--k, s);
    float hi = hs_boundary(k + 1, s);
    while (k < HS_LAYERS - 1 && depth >= hi) {
        lo = hi;
        hi = hs_boundary(++k + 1, s);
    }
    return hs_position_in(k, depth, lo, hi);
}

int hs_assign(float depth) {
#if HS_LAYERS <= 16
    // As planar_slices::assign counts them for a few maps: the boundaries D_1..D_N at or before the
    // depth (none for NaN), without locate's settling loops and fraction.
    vec2 s = hs_slices(hs_map_extent());
    int k = 0;
    for (int i = 1; i <= HS_LAYERS; ++i) k += depth >= hs_boundary(i, s) ? 1 : 0;
    return min(k, HS_LAYERS - 1);
#else
    return clamp(hs_locate(depth).index, 0, HS_LAYERS - 1);
#endif
}
