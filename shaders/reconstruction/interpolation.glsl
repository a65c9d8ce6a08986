// Reconstruction by interpolation: linear optical depth inside the layer a depth falls in. The method
// provides hs_through_layer(k), the optical depth in front of the end of layer k (a prefix sum for
// histogram bins). Mirrors hairshadow::interpolation.
float hs_interpolate(hs_layer_position p) {
    if (p.index < 0) return 0.0;
    if (p.index >= HS_LAYERS) return hs_through_layer(HS_LAYERS - 1);
    float before = p.index > 0 ? hs_through_layer(p.index - 1) : 0.0;
    float after = hs_through_layer(p.index);
    return before + p.fraction * (after - before);
}

// The optical depth the look-up turns into T; a reconstruction built on this one defines its own
// after this file (HS_OWN_OPTICAL_DEPTH: hair_count).
#ifndef HS_OWN_OPTICAL_DEPTH
float hs_optical_depth(hs_layer_position p) { return hs_interpolate(p); }
#endif
