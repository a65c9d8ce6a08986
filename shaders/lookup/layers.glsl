// The stored layers of an interpolated method at the look-up's texel: hs_through_layer(k) is the
// optical depth in front of the end of layer k. Layers are channels of a 2D array texture (four per
// array layer); HS_CUMULATIVE layers hold it directly, histogram bins are summed. A port to another
// shading language fetches the same values itself and calls reconstruction/interpolation's
// hs_interpolate_from (docs/texel_layouts.md).
uniform sampler2DArray hs_layers_texture;
ivec2 hs_lookup_texel;

float hs_stored_layer(int k) { return hs_decode(texelFetch(hs_layers_texture, ivec3(hs_lookup_texel, k / 4), 0)[k % 4]); }

float hs_through_layer(int k) {
#ifdef HS_CUMULATIVE
    return hs_stored_layer(k);
#else
    float sum = 0.0;
    for (int i = 0; i <= k; ++i) sum += hs_stored_layer(i);
    return sum;
#endif
}
