// Deep opacity maps' per-texel state from the depth-range map: z0 is its nearest fragment; with
// HS_BEYOND_EXTEND the layers stretch to reach the furthest (the smallest float above furthest - z0,
// as the CPU's std::nextafter gives).
float hs_scale_from(vec4 range) {
#ifdef HS_BEYOND_EXTEND
    return max(1.0, hs_div_rn(hs_just_above(range.w - range.x), hs_layer_extent()));
#else
    return 1.0;
#endif
}
int hs_assign_from(ivec2 texel, vec4 range, float depth) { return hs_assign(range.x, hs_scale_from(range), depth); }
hs_layer_position hs_locate_from(ivec2 texel, vec4 range, float depth) { return hs_locate(range.x, hs_scale_from(range), depth); }
