// Slab pass (Sintorn & Assarsson 2009, section 3.1): the fragment's optical depth added to its slab's
// channel of RGBA targets (4 slabs each; RGBA32F, or RGBA8 for emulated 8 bits) by additive blending.
layout(location = 0) out vec4 hs_slabs_out[HS_SLAB_TARGETS];

void main() {
    vec4 range = texelFetch(hs_range_map, ivec2(gl_FragCoord.xy), 0);
    int k = hs_assign_from(ivec2(gl_FragCoord.xy), range, hs_fragment_depth());
    if (k < 0) discard;
    int slab = k / (HS_LAYERS / HS_SLABS);
    vec4 value = vec4(0.0);
    value[slab % 4] = hs_encode(hs_fragment_optical_depth());
    for (int t = 0; t < HS_SLAB_TARGETS; ++t) hs_slabs_out[t] = (slab / 4 == t) ? value : vec4(0.0);
}
