// Per-texel lists of fragments (depth, optical depth), as the AVSM paper gathers its occluders: each
// fragment takes the next record of one buffer and links itself in front of its texel's list, whose
// length it counts. A record past the buffer's end is counted but not written: the build reads the
// count back, grows the buffer and walks again. Fragments of no optical depth, or of no finite depth,
// change no map and are left out; a depth of -0 is stored as 0, as the CPU sorts it.
struct hs_listed_fragment {
    float depth;
    float b;
    uint next;
};
// Per texel: its list's first record, then its length.
layout(std430, binding = 4) buffer hs_list_head_buffer { uint hs_list_heads[]; };
layout(std430, binding = 5) buffer hs_list_buffer {
    uint hs_listed_count;
    uint hs_list_status; // 1: a texel's list was not taken whole (see compute/resolve_nodes)
    hs_listed_fragment hs_listed[];
};
const uint HS_LIST_END = 0xffffffffu;

void hs_append_fragment(uint texel, float depth, float b) {
    if (!(b > 0.0) || isnan(depth) || isinf(depth)) return;
    uint index = atomicAdd(hs_listed_count, 1u);
    if (index >= uint(hs_listed.length())) return;
    hs_listed[index].depth = floatBitsToUint(depth) == 0x80000000u ? 0.0 : depth; // by its bits: no compiler folds this away
    hs_listed[index].b = b;
    hs_listed[index].next = atomicExchange(hs_list_heads[2u * texel], index);
    atomicAdd(hs_list_heads[2u * texel + 1u], 1u);
}
