// float hs_transmittance(vec3 world_pos) for interpolated methods (opacity shadow maps, deep opacity
// maps, density clustering, range opacity maps, hair count): any user shader can call it.
float hs_transmittance(vec3 world_pos) {
    float depth;
    vec4 range;
    if (!hs_lookup_locate(world_pos, hs_lookup_texel, depth, range)) return 1.0;
    return exp(-hs_optical_depth(hs_locate_from(hs_lookup_texel, range, depth)));
}
