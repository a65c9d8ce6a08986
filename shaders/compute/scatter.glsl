// Compute build, step 3 (one invocation per segment): each drawn short segment's index into the list
// of every tile its box meets, and each long segment that prepare counted in tiles into theirs. The
// order within a tile does not matter: every later sum is exact.
layout(local_size_x = 256) in;
void hs_emit(int x, int y) {} // this pass walks no lines
uniform uint hs_segment_count;

void main() {
    uint i = hs_segment_index();
    if (i >= hs_segment_count) return;
    if (i < hs_long_binned) { // the long segments prepare counted in tiles, one an invocation
        uint segment = hs_binned[hs_long_first + hs_segment_count - 1u - i];
        ivec4 long_box;
        if (hs_segment_box(hs_segments[segment].ends, long_box)) hs_long_tiles(hs_segments[segment].ends, long_box, 2, segment);
    }
    ivec4 ends = hs_segments[i].ends, box;
    if (ends.xy == ends.zw || !hs_segment_box(ends, box)) return;
    ivec4 tiles = box / HS_TILE;
    if ((tiles.z - tiles.x + 1) * (tiles.w - tiles.y + 1) > HS_SHORT_TILES) return; // long: listed above, or in the long list
    for (int ty = tiles.y; ty <= tiles.w; ++ty)
        for (int tx = tiles.x; tx <= tiles.z; ++tx) {
            uint tile = uint(ty * hs_tiles_x + tx);
            hs_binned[hs_tile_offsets[tile] + atomicAdd(hs_tile_counts[tile], 1u)] = i;
        }
}
