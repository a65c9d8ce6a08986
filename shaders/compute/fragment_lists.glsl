// The compute path's list pass (one work group per tile): every fragment of the tile's segments, as the
// CPU's tiled build makes it, appended to its texel's list (passes/fragment_lists).
layout(local_size_x = 16, local_size_y = 16) in;

void hs_emit(int x, int y) {
    float depth, b;
    hs_shade(x, y, depth, b);
    hs_append_fragment(uint(y) * uint(hs_resolution) + uint(x), depth, b);
}

void main() { hs_walk_tile(gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x); }
