// Occupancy maps' per-texel depth range (Sintorn & Assarsson 2009, section 3.1): HS_LAYERS slices
// between the texel's nearest and furthest fragment, settled against the slice boundaries so that a
// fragment's slice and a query's agree exactly. Mirrors depth_range; hs_range = (nearest, furthest).
float hs_boundary(vec2 hs_range, int k) {
    precise float value = hs_range.x + (hs_range.y - hs_range.x) * hs_div_rn(float(k), float(HS_LAYERS));
    return value;
}

int hs_slice_of(vec2 hs_range, float depth) {
    int k = hs_estimate_index((depth - hs_range.x) / (hs_range.y - hs_range.x) * float(HS_LAYERS), HS_LAYERS);
    while (k > 0 && depth < hs_boundary(hs_range, k)) --k;
    while (k < HS_LAYERS && depth >= hs_boundary(hs_range, k + 1)) ++k;
    return k;
}

int hs_assign(vec2 hs_range, float depth) {
    if (!(hs_range.y > hs_range.x)) return 0;
    return clamp(hs_slice_of(hs_range, depth), 0, HS_LAYERS - 1);
}

hs_layer_position hs_locate(vec2 hs_range, float depth) {
    if (!(hs_range.y > hs_range.x)) return depth > hs_range.x ? hs_layer_position(HS_LAYERS, 0.0) : hs_layer_position(-1, 0.0);
    if (!(depth >= hs_range.x)) return hs_layer_position(-1, 0.0);
    int k = hs_slice_of(hs_range, depth);
    if (k >= HS_LAYERS) return hs_layer_position(HS_LAYERS, 0.0);
    return hs_position_in(k, depth, hs_boundary(hs_range, k), hs_boundary(hs_range, k + 1));
}
