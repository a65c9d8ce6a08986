// Where a depth falls among a texel's layers: index -1 in front of all, HS_LAYERS behind all,
// otherwise a fraction of the way through layer `index`. Mirrors hairshadow::layer_position.
struct hs_layer_position {
    int index;
    float fraction;
};

hs_layer_position hs_position_in(int k, float depth, float lo, float hi) {
    return hs_layer_position(k, hi > lo ? clamp((depth - lo) / (hi - lo), 0.0, 1.0) : 0.0);
}

// The largest integer in [0, last] no greater than a non-negative estimate; NaN and negatives give 0.
int hs_estimate_index(float estimate, int last) { return estimate > 0.0 ? int(min(estimate, float(last))) : 0; }
