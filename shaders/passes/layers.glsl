// Accumulation pass of interpolated methods (Kim & Neumann 2001; Yuksel & Keyser 2008): the
// fragment's encoded optical depth goes to its layer's channel (HS_CUMULATIVE: and to every later
// layer's), layers [hs_first_layer, hs_first_layer + 4 HS_LAYER_TARGETS) in this pass, by additive
// blending into RGBA32F (float) or RGBA8 (emulated 8-bit) layers of a 2D array texture.
uniform int hs_first_layer;
layout(location = 0) out vec4 hs_layers_out[HS_LAYER_TARGETS];

void main() {
    vec4 range = texelFetch(hs_range_map, ivec2(gl_FragCoord.xy), 0);
    int k = hs_assign_from(ivec2(gl_FragCoord.xy), range, hs_fragment_depth());
    float value = k < 0 ? 0.0 : hs_encode(hs_fragment_optical_depth());
    for (int t = 0; t < HS_LAYER_TARGETS; ++t) {
        vec4 v = vec4(0.0);
        for (int c = 0; c < 4; ++c) {
            int layer = hs_first_layer + 4 * t + c;
#ifdef HS_CUMULATIVE
            v[c] = (k >= 0 && layer >= k && layer < HS_LAYERS) ? value : 0.0;
#else
            v[c] = layer == k ? value : 0.0;
#endif
        }
        hs_layers_out[t] = v;
    }
}
