// Unreal Engine's deep shadow layers (HairStrands): boundary k, for k = 1..HS_LAYERS, lies at
// z0 + D hs_power_fraction[k] behind the texel's first fragment z0, D being the map's depth extent
// and the fractions (k / (K + 1))^e as the CPU rounded them. A fragment starts adding at the first
// boundary it is not in front of (-1 behind the last); a query moves back by 0.05 of the first
// boundary. Mirrors hairshadow::power_layers, float for float (precise: no fused products).
uniform float hs_power_fraction[HS_LAYERS + 1];

// The hair's depth D (the map's extent), read once per fragment or query, and boundary k of it.
float hs_power_depth() {
    vec2 extent = hs_map_extent();
    precise float depth = max(extent.y - extent.x, 1e-6);
    return depth;
}
float hs_power_boundary(float depth, int k) {
    precise float boundary = depth * hs_power_fraction[k];
    return k == 0 ? 0.0 : boundary;
}

int hs_assign_from(ivec2 texel, vec4 range, float depth) {
    float hair_depth = hs_power_depth();
    precise float behind = depth - range.x;
    int k = 0;
    for (int i = 1; i <= HS_LAYERS; ++i) k += behind >= hs_power_boundary(hair_depth, i) ? 1 : 0;
    return k == HS_LAYERS ? -1 : k;
}

hs_layer_position hs_locate_from(ivec2 texel, vec4 range, float depth) {
    float hair_depth = hs_power_depth();
    precise float behind = depth - range.x;
    if (!(behind >= 0.0)) return hs_layer_position(-1, 0.0);
    precise float bias = 0.05 * hs_power_boundary(hair_depth, 1);
    precise float d = max(behind - bias, 0.0);
    if (d >= hs_power_boundary(hair_depth, HS_LAYERS)) return hs_layer_position(HS_LAYERS, 0.0);
    int k = 0;
    for (int i = 1; i < HS_LAYERS; ++i) k += d >= hs_power_boundary(hair_depth, i) ? 1 : 0;
    return hs_position_in(k, d, hs_power_boundary(hair_depth, k), hs_power_boundary(hair_depth, k + 1));
}
