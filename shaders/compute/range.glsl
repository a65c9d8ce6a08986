// Compute build, step 4 (one work group per tile): each texel's nearest and furthest fragment, by
// atomic minimum and maximum in shared memory, written as the light pass's range map (nearest in red,
// furthest in alpha; red > alpha where no fragment fell).
layout(local_size_x = 16, local_size_y = 16) in;
layout(rgba32f) writeonly uniform image2D hs_range_image;

shared uint hs_nearest[256], hs_furthest[256];
ivec2 hs_origin;

void hs_emit(int x, int y) {
    uint k = uint((y - hs_origin.y) * HS_TILE + (x - hs_origin.x));
    uint d = hs_ordered(hs_fragment_depth_of(x, y));
    atomicMin(hs_nearest[k], d);
    atomicMax(hs_furthest[k], d);
}

void main() {
    uint tile = gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x;
    hs_origin = hs_tile_rect(tile).xy;
    uint k = gl_LocalInvocationIndex;
    hs_nearest[k] = 0xffffffffu;
    hs_furthest[k] = 0u;
    barrier();
    hs_walk_tile(tile);
    barrier();
    ivec2 texel = hs_origin + ivec2(gl_LocalInvocationID.xy);
    if (texel.x >= hs_resolution || texel.y >= hs_resolution) return;
    bool empty = hs_nearest[k] == 0xffffffffu;
    imageStore(hs_range_image, texel, empty ? vec4(3.0e38, 0.0, 0.0, -3.0e38) : vec4(hs_from_ordered(hs_nearest[k]), 0.0, 0.0, hs_from_ordered(hs_furthest[k])));
}
