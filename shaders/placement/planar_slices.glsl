// Opacity shadow maps' planar slices (Kim & Neumann 2001, section 2): HS_LAYERS maps between D_0 (the
// nearest fragment of the whole map) and D_N (just beyond the furthest); uniform spacing, or
// D_i = D_0 + (D_N - D_0)(i/N)^2 when HS_GAMMA_SPACING is defined. Mirrors planar_slices.
uniform float hs_slices_near;
uniform float hs_slices_far;

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

float hs_boundary(int i) {
    precise float value = i >= HS_LAYERS ? hs_slices_far
                                         : hs_slices_near + (hs_slices_far - hs_slices_near) * hs_spacing(float(i) / float(HS_LAYERS));
    return value;
}

hs_layer_position hs_locate(float depth) {
    if (!(depth >= hs_slices_near)) return hs_layer_position(-1, 0.0);
    if (depth >= hs_slices_far) return hs_layer_position(HS_LAYERS, 0.0);
    int k = hs_estimate_index(hs_spacing_inverse((depth - hs_slices_near) / (hs_slices_far - hs_slices_near)) * float(HS_LAYERS), HS_LAYERS - 1);
    while (k > 0 && depth < hs_boundary(k)) --k;
    while (k < HS_LAYERS - 1 && depth >= hs_boundary(k + 1)) ++k;
    return hs_position_in(k, depth, hs_boundary(k), hs_boundary(k + 1));
}

int hs_assign(float depth) { return clamp(hs_locate(depth).index, 0, HS_LAYERS - 1); }
