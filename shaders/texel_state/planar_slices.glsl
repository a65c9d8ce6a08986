// Planar slices keep no per-texel state: the slices are global (placement/planar_slices' hs_slices).
int hs_assign_from(ivec2 texel, vec4 range, float depth) { return hs_assign(depth); }
hs_layer_position hs_locate_from(ivec2 texel, vec4 range, float depth) { return hs_locate(depth); }
