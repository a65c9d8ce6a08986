// Look-up of adaptive volumetric shadow maps: the texel's nodes, two to an array layer, and T from
// reconstruction/adaptive_nodes. The light's frustum and the range map (which says where a texel holds
// no fragment) are lookup/light's. hs_nodes_transmittance(depths, omegas, depth) is the plain look-up
// over fetched nodes that a port to another shading language calls (docs/texel_layouts.md).
uniform sampler2DArray hs_nodes_texture;

float hs_transmittance(vec3 world_pos) {
    ivec2 texel;
    float depth;
    vec4 range;
    if (!hs_lookup_locate(world_pos, texel, depth, range)) return 1.0;
    float depths[HS_NODES], omegas[HS_NODES];
    for (int layer = 0; layer < HS_NODES / 2; ++layer) {
        vec4 v = texelFetch(hs_nodes_texture, ivec3(texel, layer), 0);
        depths[2 * layer] = v.x;
        omegas[2 * layer] = v.y;
        depths[2 * layer + 1] = v.z;
        omegas[2 * layer + 1] = v.w;
    }
    return hs_nodes_transmittance(depths, omegas, depth);
}
