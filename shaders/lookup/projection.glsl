// Look-up of the projected methods (Fourier opacity maps, moment shadow maps), mirroring
// reconstruction/detail/depth_projection.hpp: no shadow in front of the texel's nearest fragment, its
// whole optical depth behind the furthest, and between them the reconstruction's series, held within
// [0, total]. The range map and the light's frustum are lookup/light's.
uniform sampler2DArray hs_sums_texture;

// The plain look-up over a texel's sums as stored (fetched by the caller: a port to another shading
// language calls it after its own fetches; docs/texel_layouts.md), its nearest and furthest fragment
// (the range map's red and alpha) and the query's depth: T.
float hs_projected_transmittance(float sums[HS_SUMS], float nearest, float furthest, float depth) {
    hs_decode_sums(sums);
    float total = hs_total_optical_depth(sums);
    if (!(depth > nearest) || !(total > 0.0)) return 1.0;
    if (depth > furthest) return exp(-total);
    float tau = hs_series_optical_depth(sums, hs_position_in_range(nearest, furthest, depth));
    return exp(-(tau > 0.0 ? min(tau, total) : 0.0)); // NaN (a singular moment matrix) casts none, as on the CPU
}

float hs_transmittance(vec3 world_pos) {
    ivec2 texel;
    float depth;
    vec4 range;
    if (!hs_lookup_locate(world_pos, texel, depth, range)) return 1.0;
    float sums[HS_SUMS];
    for (int layer = 0; layer < (HS_SUMS + 3) / 4; ++layer) {
        vec4 v = texelFetch(hs_sums_texture, ivec3(texel, layer), 0);
        for (int c = 0; c < 4 && 4 * layer + c < HS_SUMS; ++c) sums[4 * layer + c] = v[c];
    }
    return hs_projected_transmittance(sums, range.x, range.w, depth);
}
