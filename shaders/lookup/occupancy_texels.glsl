// The occupancy maps' textures (HS_BIT_TARGETS of RGBA32UI words, HS_SLAB_TARGETS of 4 slabs each)
// and one texel's words and slabs read from them.
uniform usampler2D hs_bits_texture[HS_BIT_TARGETS];
uniform sampler2D hs_slabs_texture[HS_SLAB_TARGETS];

void hs_fetch_occupancy(ivec2 texel, out uint bits[HS_WORDS], out float slabs[HS_SLABS]) {
    for (int w = 0; w < HS_WORDS; ++w) bits[w] = texelFetch(hs_bits_texture[w / 4], texel, 0)[w % 4];
    for (int s = 0; s < HS_SLABS; ++s) slabs[s] = texelFetch(hs_slabs_texture[s / 4], texel, 0)[s % 4];
}
