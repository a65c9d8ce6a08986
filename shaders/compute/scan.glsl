// Compute build, step 2 (one work group): the tiles' segment counts to offsets (an exclusive prefix
// sum), the counts back to zero as the scatter's cursors, the number of segment-tile pairs, and the
// whole map's extent into the range map's extra row (nearest, 0, 0, furthest; zero when no segment
// meets the map), where placement/common's hs_map_extent reads it.
layout(local_size_x = 256) in;
void hs_emit(int x, int y) {} // this pass walks no lines
layout(rgba32f) writeonly uniform image2D hs_range_image;
uniform uint hs_tile_total;

shared uint hs_partial[256];

void main() {
    uint t = gl_LocalInvocationIndex;
    uint chunk = (hs_tile_total + 255u) / 256u;
    uint begin = min(t * chunk, hs_tile_total), end = min(begin + chunk, hs_tile_total);
    uint sum = 0u;
    for (uint i = begin; i < end; ++i) sum += hs_tile_counts[i];
    hs_partial[t] = sum;
    barrier();
    if (t == 0u) {
        uint running = 0u;
        for (uint i = 0u; i < 256u; ++i) {
            uint n = hs_partial[i];
            hs_partial[i] = running;
            running += n;
        }
        hs_tile_offsets[hs_tile_total] = running;
        hs_pairs = running;
        bool empty = hs_nearest_bits == 0xffffffffu;
        vec4 extent = empty ? vec4(0.0) : vec4(hs_from_ordered(hs_nearest_bits), 0.0, 0.0, hs_from_ordered(hs_furthest_bits));
        imageStore(hs_range_image, ivec2(0, hs_resolution), extent);
    }
    barrier();
    uint offset = hs_partial[t];
    for (uint i = begin; i < end; ++i) {
        hs_tile_offsets[i] = offset;
        offset += hs_tile_counts[i];
        hs_tile_counts[i] = 0u;
    }
}
