// Reconstruction by interpolation: linear optical depth inside the layer a depth falls in. The method
// provides hs_through_layer(k), the optical depth in front of the end of layer k (a prefix sum for
// histogram bins). Mirrors hairshadow::interpolation.

// The optical depth a fraction of the way through a layer, from the optical depths in front of its
// start (before) and its end (after).
float hs_interpolate_between(float before, float after, float fraction) { return before + fraction * (after - before); }

// The plain look-up over values fetched by the caller (a port to another shading language calls it
// after its own fetches; docs/texel_layouts.md): before = hs_through_layer(p.index - 1), 0 for index 0,
// and after = hs_through_layer(p.index); behind every layer (p.index >= HS_LAYERS) after =
// hs_through_layer(HS_LAYERS - 1) and before is unused; in front of all (p.index < 0) neither is read.
float hs_interpolate_from(hs_layer_position p, float before, float after) {
    if (p.index < 0) return 0.0;
    if (p.index >= HS_LAYERS) return after;
    return hs_interpolate_between(before, after, p.fraction);
}

// The same fetching through hs_through_layer, only the layers it needs.
float hs_interpolate(hs_layer_position p) {
    if (p.index < 0) return 0.0;
    if (p.index >= HS_LAYERS) return hs_through_layer(HS_LAYERS - 1);
    float before = p.index > 0 ? hs_through_layer(p.index - 1) : 0.0;
    float after = hs_through_layer(p.index);
    return hs_interpolate_between(before, after, p.fraction);
}

// The optical depth the look-up turns into T; a reconstruction built on this one defines its own
// after this file (HS_OWN_OPTICAL_DEPTH: hair_count).
#ifndef HS_OWN_OPTICAL_DEPTH
float hs_optical_depth(hs_layer_position p) { return hs_interpolate(p); }
#endif
