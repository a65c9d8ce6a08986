// Deep opacity maps' per-pixel layers (Yuksel & Keyser 2008, section 3): layer k spans
// [z0 + d_{k-1}, z0 + d_k), d_k = d_K k(k+1) / (K(K+1)) (linear sizes) or d_K k / K when
// HS_UNIFORM_SIZES is defined; beyond d_K fragments clamp into the last layer, are dropped
// (HS_BEYOND_IGNORE) or the layers stretch to the texel's last fragment (HS_BEYOND_EXTEND, with the
// stretch factor in hs_scale). Mirrors per_pixel_depth, whose prepare() takes d_K from the map's
// extent as hs_layer_extent() does unless the placement was given one.
uniform float hs_requested_extent; // d_K in linear depth as given to the placement; 0: the default

float hs_layer_extent() {
    if (hs_requested_extent > 0.0) return hs_requested_extent;
    vec2 extent = hs_map_extent();
    precise float half_range = 0.5 * (extent.y - extent.x);
    return max(half_range, 1e-6);
}

#ifdef HS_RELATIVE_BOUNDARY_BITS
// d_k / d_K for k in [0, HS_LAYERS]: the CPU's table (per_pixel_depth::relative_boundaries), as bits.
const uint hs_relative_boundary_bits[HS_LAYERS + 1] = HS_RELATIVE_BOUNDARY_BITS;
float hs_relative_boundary(int k) { return uintBitsToFloat(hs_relative_boundary_bits[k]); }
#else
float hs_relative_boundary(int k) {
#ifdef HS_UNIFORM_SIZES
    return hs_div_rn(float(k), float(HS_LAYERS));
#else
    return hs_div_rn(float(k * (k + 1)), float(HS_LAYERS * (HS_LAYERS + 1)));
#endif
}
#endif

hs_layer_position hs_locate(float z0, float hs_scale, float depth) {
    precise float extent = hs_layer_extent() * hs_scale;
    float rel = hs_div_rn(depth - z0, extent);
    if (!(rel >= 0.0)) return hs_layer_position(-1, 0.0);
    if (rel >= 1.0) return hs_layer_position(HS_LAYERS, 0.0);
#ifdef HS_UNIFORM_SIZES
    float estimate = rel * float(HS_LAYERS);
#else
    float estimate = (sqrt(1.0 + 4.0 * rel * float(HS_LAYERS * (HS_LAYERS + 1))) - 1.0) * 0.5;
#endif
    int k = hs_estimate_index(estimate, HS_LAYERS - 1);
    // The estimate settled by exact comparisons, carrying the boundaries it compared with so that
    // each is worked out once (an hs_div_rn where the placement gave no table).
    float lo = hs_relative_boundary(k);
    while (k > 0 && rel < lo) lo = hs_relative_boundary(--k);
    float hi = hs_relative_boundary(k + 1);
    while (k < HS_LAYERS - 1 && rel >= hi) {
        lo = hi;
        hi = hs_relative_boundary(++k + 1);
    }
    return hs_position_in(k, rel, lo, hi);
}

int hs_assign(float z0, float hs_scale, float depth) {
#if HS_LAYERS <= 8
    // As per_pixel_depth::assign counts it for a few layers: the boundaries d_1..d_K the relative
    // depth has reached (none for NaN), without locate's settling loops and fraction, which a
    // fragment's layer does not need.
    precise float extent = hs_layer_extent() * hs_scale;
    float rel = hs_div_rn(depth - z0, extent);
    int k = 0;
    for (int i = 1; i <= HS_LAYERS; ++i) k += rel >= hs_relative_boundary(i) ? 1 : 0;
#ifdef HS_BEYOND_IGNORE
    return k == HS_LAYERS ? -1 : k;
#else
    return min(k, HS_LAYERS - 1);
#endif
#else
    hs_layer_position p = hs_locate(z0, hs_scale, depth);
    if (p.index < 0) return 0;
#ifdef HS_BEYOND_IGNORE
    if (p.index >= HS_LAYERS) return -1;
#endif
    return min(p.index, HS_LAYERS - 1);
#endif
}
