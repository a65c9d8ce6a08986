// Occupancy maps' per-texel state: the depth-range map itself (nearest in red, furthest in alpha).
int hs_assign_from(ivec2 texel, vec4 range, float depth) { return hs_assign(vec2(range.x, range.w), depth); }
hs_layer_position hs_locate_from(ivec2 texel, vec4 range, float depth) { return hs_locate(vec2(range.x, range.w), depth); }
