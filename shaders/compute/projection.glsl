// Compute build of the projected methods (Fourier opacity maps, moment shadow maps; one work group per
// tile): every fragment's HS_SUMS terms (hs_added_terms at its place in the texel's depth range) summed
// in fixed point (or, HS_EIGHT_BIT, as integer 8-bit steps), HS_SUM_SLOTS (a multiple of 4) of them per walk of the tile's segments;
// then each texel's sums into the sums texture, four to an array layer, where the raster pass blends
// them.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0, HS_SUMS_FORMAT) writeonly uniform image2DArray hs_sums_image;

shared vec2 hs_texel_range[256];
ivec2 hs_origin;
int hs_group_first;

void hs_emit(int x, int y) {
    uint texel = uint((y - hs_origin.y) * HS_TILE + (x - hs_origin.x));
    float depth, b;
    hs_shade(x, y, depth, b);
    vec2 range = hs_texel_range[texel];
    float terms[HS_SUMS];
    hs_added_terms(hs_position_in_range(range.x, range.y, depth), b, terms);
    for (int k = 0; k < HS_SUM_SLOTS && hs_group_first + k < HS_SUMS; ++k) hs_add_sum(texel * uint(HS_SUM_SLOTS) + uint(k), terms[hs_group_first + k]);
}

void main() {
    uint tile = gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x;
    hs_origin = hs_tile_rect(tile).xy;
    uint me = gl_LocalInvocationIndex;
    ivec2 texel = hs_origin + ivec2(gl_LocalInvocationID.xy);
    bool inside = texel.x < hs_resolution && texel.y < hs_resolution;
    vec4 range = inside ? texelFetch(hs_range_map, texel, 0) : vec4(0.0);
    hs_texel_range[me] = range.xw;
    for (hs_group_first = 0; hs_group_first < HS_SUMS; hs_group_first += HS_SUM_SLOTS) {
        hs_clear_sums();
        barrier();
        hs_walk_tile(tile);
        barrier();
        if (inside) {
            for (int layer = hs_group_first / 4; layer < (min(hs_group_first + HS_SUM_SLOTS, HS_SUMS) + 3) / 4; ++layer) {
                vec4 v = vec4(0.0);
                for (int c = 0; c < 4 && 4 * layer + c < HS_SUMS; ++c) {
                    uint slot = me * uint(HS_SUM_SLOTS) + uint(4 * layer + c - hs_group_first);
#ifdef HS_EIGHT_BIT
                    v[c] = hs_stored(hs_sum(slot));
#else
                    v[c] = hs_stored_signed(hs_sum(slot)); // the terms may be negative
#endif
                }
                imageStore(hs_sums_image, ivec3(texel, layer), v);
            }
        }
        barrier();
    }
}
