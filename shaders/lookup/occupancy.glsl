// float hs_transmittance(vec3 world_pos) for occupancy maps: any user shader can call it after the
// placement, accumulation and reconstruction snippets.
uniform usampler2D hs_bits_texture[HS_BIT_TARGETS];
uniform sampler2D hs_slabs_texture[HS_SLAB_TARGETS];

float hs_transmittance(vec3 world_pos) {
    ivec2 texel;
    float depth;
    vec4 range;
    if (!hs_lookup_locate(world_pos, texel, depth, range)) return 1.0;
    uint bits[HS_WORDS];
    for (int w = 0; w < HS_WORDS; ++w) bits[w] = texelFetch(hs_bits_texture[w / 4], texel, 0)[w % 4];
    float slabs[HS_SLABS];
    for (int s = 0; s < HS_SLABS; ++s) slabs[s] = texelFetch(hs_slabs_texture[s / 4], texel, 0)[s % 4];
    return exp(-hs_occupancy_optical_depth(hs_locate_from(texel, range, depth), bits, slabs));
}
