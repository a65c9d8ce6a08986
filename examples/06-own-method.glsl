// doubling_slices (examples/06-own-method.cpp): HS_LAYERS slices in each texel's depth range, each
// twice as deep as the one before. The CPU writes the slices' boundary fractions into HS_FRACTIONS
// (glsl_defines), each as the decimal that parses back to its own float, so that both sides place
// every boundary on the same float: nearest + span * fraction, never fused (precise).
// A placement's GLSL defines hs_assign_from and hs_locate_from, from the texel's depth-range map
// (nearest in x, furthest in w), with placement/common's hs_layer_position helpers.
const float hs_fractions[HS_LAYERS + 1] = HS_FRACTIONS;

float hs_doubling_boundary(vec2 range, int k) {
    precise float value = range.x + (range.y - range.x) * hs_fractions[k];
    return value;
}

// The k with boundary(k) <= depth < boundary(k + 1), HS_LAYERS past the last: from an estimate,
// settled against the boundaries, as the CPU's slice_of.
int hs_doubling_slice(vec2 range, float depth) {
    float rel = (depth - range.x) / (range.y - range.x);
    int k = hs_estimate_index(log2(1.0 + rel * (exp2(float(HS_LAYERS)) - 1.0)), HS_LAYERS);
    while (k > 0 && depth < hs_doubling_boundary(range, k)) --k;
    while (k < HS_LAYERS && depth >= hs_doubling_boundary(range, k + 1)) ++k;
    return k;
}

int hs_assign_from(ivec2 texel, vec4 range, float depth) {
    vec2 r = range.xw;
    if (!(r.y > r.x)) return 0;
    return clamp(hs_doubling_slice(r, depth), 0, HS_LAYERS - 1);
}

hs_layer_position hs_locate_from(ivec2 texel, vec4 range, float depth) {
    vec2 r = range.xw;
    if (!(r.y > r.x)) return depth > r.x ? hs_layer_position(HS_LAYERS, 0.0) : hs_layer_position(-1, 0.0);
    if (!(depth >= r.x)) return hs_layer_position(-1, 0.0);
    int k = hs_doubling_slice(r, depth);
    if (k >= HS_LAYERS) return hs_layer_position(HS_LAYERS, 0.0);
    return hs_position_in(k, depth, hs_doubling_boundary(r, k), hs_doubling_boundary(r, k + 1));
}
