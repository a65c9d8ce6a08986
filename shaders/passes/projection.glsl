// The projected methods' raster pass (Fourier opacity maps, moment shadow maps): each fragment adds its
// HS_SUMS terms (the reconstruction's hs_projection_terms at its place in the texel's depth range) to
// its texel, four to a target, by additive blending into RGBA32F layers of a 2D array texture (or their
// 8-bit encoding, hs_encode'd, into RGBA8 layers).
layout(location = 0) out vec4 hs_sums_out[(HS_SUMS + 3) / 4];

void main() {
    vec4 range = texelFetch(hs_range_map, ivec2(gl_FragCoord.xy), 0);
    float terms[HS_SUMS];
    hs_added_terms(hs_position_in_range(range.x, range.w, hs_fragment_depth()), hs_fragment_optical_depth(), terms);
    for (int t = 0; t < (HS_SUMS + 3) / 4; ++t) {
        vec4 v = vec4(0.0);
        for (int c = 0; c < 4 && 4 * t + c < HS_SUMS; ++c) v[c] = hs_encode(terms[4 * t + c]);
        hs_sums_out[t] = v;
    }
}
