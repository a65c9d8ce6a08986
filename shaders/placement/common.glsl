// Where a depth falls among a texel's layers: index -1 in front of all, HS_LAYERS behind all,
// otherwise a fraction of the way through layer `index`. Mirrors hairshadow::layer_position.
struct hs_layer_position {
    int index;
    float fraction;
};

hs_layer_position hs_position_in(int k, float depth, float lo, float hi) {
    return hs_layer_position(k, hi > lo ? clamp(hs_div_rn(depth - lo, hi - lo), 0.0, 1.0) : 0.0);
}

// The largest integer in [0, last] no greater than a non-negative estimate; NaN and negatives give 0.
int hs_estimate_index(float estimate, int last) { return estimate > 0.0 ? int(min(estimate, float(last))) : 0; }

// The smallest float above x, as std::nextafter(x, +inf) for the finite depths the maps hold.
float hs_just_above(float x) {
    if (x == 0.0) return uintBitsToFloat(1u);
    return x > 0.0 ? uintBitsToFloat(floatBitsToUint(x) + 1u) : -uintBitsToFloat(floatBitsToUint(-x) - 1u);
}

// The light pass's depth-range map, which every later pass and every look-up reads: nearest fragment
// in red, furthest in alpha. The first texel of its extra last row holds the whole map's extent
// (reduced on the GPU by passes/depth_extent), the global state of the placements that need one.
uniform sampler2D hs_range_map;
vec2 hs_map_extent() { return texelFetch(hs_range_map, ivec2(0, textureSize(hs_range_map, 0).y - 1), 0).xw; }
