// Compute build of the measured fibre density (one work group per tile): each texel's fragments'
// optical depth, summed as the layers pass sums it, and their count, into the RG32F texture where the
// raster pass blends them.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0, rg32f) writeonly uniform image2D hs_density_image;

shared uint hs_count[256];
ivec2 hs_origin;

void hs_emit(int x, int y) {
    uint texel = uint((y - hs_origin.y) * HS_TILE + (x - hs_origin.x));
    float depth, b;
    hs_shade(x, y, depth, b);
    hs_add_sum(texel, b);
    atomicAdd(hs_count[texel], 1u);
}

void main() {
    uint tile = gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x;
    hs_origin = hs_tile_rect(tile).xy;
    uint me = gl_LocalInvocationIndex;
    hs_count[me] = 0u;
    hs_clear_sums();
    barrier();
    hs_walk_tile(tile);
    barrier();
    ivec2 texel = hs_origin + ivec2(gl_LocalInvocationID.xy);
    if (texel.x < hs_resolution && texel.y < hs_resolution) imageStore(hs_density_image, texel, vec4(hs_stored(hs_sum(me)), float(hs_count[me]), 0.0, 0.0));
}
