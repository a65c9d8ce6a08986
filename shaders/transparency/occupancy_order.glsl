// Occupancy-ordered blending, the blend pass (Sintorn & Assarsson 2009, section 3.4): every visible
// fragment, unsorted, adds (1 - alpha)^o alpha (colour, 1) with o its depth order from the camera's
// occupancy and slab maps, (1 - alpha)^o = exp(-optical depth in front of its slice); and its own
// -ln(1 - alpha), for the alpha correction of transparency/resolve. Additive blending.
layout(location = 0) out vec4 hs_sum_out;   // rgb: weight x colour, a: weight
layout(location = 1) out vec4 hs_total_out; // r: -ln(1 - alpha)

void main() {
    hs_camera_fragment f = hs_this_fragment();
    if (!f.visible) discard;
    ivec2 texel = ivec2(gl_FragCoord.xy);
    uint bits[HS_WORDS];
    float slabs[HS_SLABS];
    hs_fetch_occupancy(texel, bits, slabs);
    int k = hs_assign_from(texel, texelFetch(hs_range_map, texel, 0), f.depth);
    float weight = exp(-hs_occupancy_optical_depth_in_front(k, bits, slabs)) * f.alpha;
    hs_sum_out = vec4(weight * f.colour, weight);
    hs_total_out = vec4(-log(1.0 - f.alpha), 0.0, 0.0, 0.0);
}
