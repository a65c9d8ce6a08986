// Compute build of occupancy maps (one work group per tile): each fragment's slice bit OR-ed into the
// texel's words, and its optical depth summed into its slab; then the bits (128 to an RGBA32UI
// texture) and the slabs (4 to an RGBA texture) written where the raster passes put them.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0, rgba32ui) writeonly uniform uimage2D hs_bits_images[HS_BIT_TARGETS];
layout(binding = HS_BIT_TARGETS, HS_SLABS_FORMAT) writeonly uniform image2D hs_slab_images[HS_SLAB_TARGETS];

const int HS_WORDS = HS_LAYERS / 32;
shared uint hs_bits[256 * HS_WORDS];
shared vec2 hs_texel_range[256];
ivec2 hs_origin;

void hs_emit(int x, int y) {
    uint texel = uint((y - hs_origin.y) * HS_TILE + (x - hs_origin.x));
    float depth, b;
    hs_shade(x, y, depth, b);
    vec2 range = hs_texel_range[texel];
    int k = hs_assign_from(ivec2(x, y), vec4(range.x, 0.0, 0.0, range.y), depth);
    if (k < 0) return;
    atomicOr(hs_bits[texel * uint(HS_WORDS) + uint(k / 32)], 1u << uint(k % 32));
    hs_add_sum(texel * uint(HS_SUM_SLOTS) + uint(k / (HS_LAYERS / HS_SLABS)), b);
}

void main() {
    uint tile = gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x;
    hs_origin = hs_tile_rect(tile).xy;
    uint me = gl_LocalInvocationIndex;
    ivec2 texel = hs_origin + ivec2(gl_LocalInvocationID.xy);
    bool inside = texel.x < hs_resolution && texel.y < hs_resolution;
    vec4 range = inside ? texelFetch(hs_range_map, texel, 0) : vec4(0.0);
    hs_texel_range[me] = range.xw;
    for (int w = 0; w < HS_WORDS; ++w) hs_bits[me * uint(HS_WORDS) + uint(w)] = 0u;
    hs_clear_sums();
    barrier();
    hs_walk_tile(tile);
    barrier();
    if (!inside) return;
    for (int t = 0; t < HS_BIT_TARGETS; ++t) {
        uvec4 v = uvec4(0u);
        for (int c = 0; c < 4 && 4 * t + c < HS_WORDS; ++c) v[c] = hs_bits[me * uint(HS_WORDS) + uint(4 * t + c)];
        imageStore(hs_bits_images[t], texel, v);
    }
    for (int t = 0; t < HS_SLAB_TARGETS; ++t) {
        vec4 v = vec4(0.0);
        for (int c = 0; c < 4 && 4 * t + c < HS_SLABS; ++c) v[c] = hs_stored(hs_sum(me * uint(HS_SUM_SLOTS) + uint(4 * t + c)));
        imageStore(hs_slab_images[t], texel, v);
    }
}
