// Compute build of interpolated methods (one work group per tile): every fragment's optical depth
// into the slot of its layer, HS_LAYER_GROUP layers per walk of the tile's segments; then each texel's
// layers (HS_CUMULATIVE: summed front to back, as the CPU's interpolation::build does) into the
// layers texture, four to an array layer, exactly where the raster passes blend them.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0, HS_LAYERS_FORMAT) writeonly uniform image2DArray hs_layers_image;

shared vec2 hs_texel_range[256];
ivec2 hs_origin;
int hs_group_first;

void hs_emit(int x, int y) {
    uint texel = uint((y - hs_origin.y) * HS_TILE + (x - hs_origin.x));
    float depth, b;
    hs_shade(x, y, depth, b);
    vec2 range = hs_texel_range[texel];
    int k = hs_assign_from(ivec2(x, y), vec4(range.x, 0.0, 0.0, range.y), depth) - hs_group_first;
    if (k >= 0 && k < HS_LAYER_GROUP) hs_add_sum(texel * uint(HS_SUM_SLOTS) + uint(k), b);
}

void main() {
    uint tile = gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x;
    hs_origin = hs_tile_rect(tile).xy;
    uint me = gl_LocalInvocationIndex;
    ivec2 texel = hs_origin + ivec2(gl_LocalInvocationID.xy);
    bool inside = texel.x < hs_resolution && texel.y < hs_resolution;
    vec4 range = inside ? texelFetch(hs_range_map, texel, 0) : vec4(0.0);
    hs_texel_range[me] = range.xw;
    uvec2 running = uvec2(0u); // the sum so far, (low, high) words
    for (hs_group_first = 0; hs_group_first < HS_LAYERS; hs_group_first += HS_LAYER_GROUP) {
        hs_clear_sums();
        barrier();
        hs_walk_tile(tile);
        barrier();
        if (inside) {
            for (int array_layer = hs_group_first / 4; array_layer < min(hs_group_first + HS_LAYER_GROUP, HS_LAYERS + 3) / 4; ++array_layer) {
                vec4 v = vec4(0.0);
                for (int c = 0; c < 4; ++c) {
                    int layer = 4 * array_layer + c;
                    if (layer >= HS_LAYERS) break;
                    uvec2 sum = hs_sum(me * uint(HS_SUM_SLOTS) + uint(layer - hs_group_first));
#ifdef HS_CUMULATIVE
                    running = hs_combine(running, sum);
                    v[c] = hs_stored(running);
#else
                    v[c] = hs_stored(sum);
#endif
                }
                imageStore(hs_layers_image, ivec3(texel, array_layer), v);
            }
        }
        barrier();
    }
}
