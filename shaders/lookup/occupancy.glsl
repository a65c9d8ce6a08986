// float hs_transmittance(vec3 world_pos) for occupancy maps: any user shader can call it after the
// placement, accumulation and reconstruction snippets and lookup/occupancy_texels. The plain look-up
// over fetched words and slabs, which a port to another shading language calls after its own fetches,
// is reconstruction/occupancy_bitcount's hs_occupancy_optical_depth(p, bits, slabs) (docs/texel_layouts.md).
float hs_transmittance(vec3 world_pos) {
    ivec2 texel;
    float depth;
    vec4 range;
    if (!hs_lookup_locate(world_pos, texel, depth, range)) return 1.0;
    uint bits[HS_WORDS];
    float slabs[HS_SLABS];
    hs_fetch_occupancy(texel, bits, slabs);
    return exp(-hs_occupancy_optical_depth(hs_locate_from(texel, range, depth), bits, slabs));
}
