// The lists resolved into adaptive nodes (one invocation per texel): the texel's list sorted in place
// by (depth, optical depth), a bottom-up merge sort of its links (n log n steps, no copy, so no limit
// on a texel's fragments), then inserted into the nodes (reconstruction/adaptive_nodes), written two to
// an RGBA32F array layer, the unused ones repeating the last, all zero where the list is empty. A
// texel that inserted fewer fragments than it listed, or whose last loop (a probe of hs_probe_steps
// steps, a uniform so that it is not unrolled) ran short, sets hs_list_status: a GL implementation
// that stops long loops (Mesa's llvmpipe ends a shader's loops after 65535 steps) cut it short, and
// the build throws rather than return wrong maps.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) writeonly uniform image2DArray hs_nodes_image;
uniform int hs_resolution;
uniform int hs_probe_steps;

bool hs_listed_before(uint a, uint b) {
    return hs_listed[a].depth < hs_listed[b].depth || (hs_listed[a].depth == hs_listed[b].depth && hs_listed[a].b <= hs_listed[b].b);
}
// Cuts the list at `from` after `count` records; returns the record after the cut (or the end).
uint hs_cut_list(uint from, uint count) {
    for (uint k = 1u; k < count && from != HS_LIST_END; ++k) from = hs_listed[from].next;
    if (from == HS_LIST_END) return HS_LIST_END;
    uint rest = hs_listed[from].next;
    hs_listed[from].next = HS_LIST_END;
    return rest;
}
uint hs_sort_list(uint head, uint n) {
    for (uint width = 1u; width < n; width *= 2u) {
        uint rest = head, tail = HS_LIST_END;
        head = HS_LIST_END;
        while (rest != HS_LIST_END) {
            uint a = rest, b = hs_cut_list(a, width);
            rest = hs_cut_list(b, width);
            while (a != HS_LIST_END || b != HS_LIST_END) {
                uint taken;
                if (b == HS_LIST_END || (a != HS_LIST_END && hs_listed_before(a, b))) {
                    taken = a;
                    a = hs_listed[a].next;
                } else {
                    taken = b;
                    b = hs_listed[b].next;
                }
                if (tail == HS_LIST_END) head = taken;
                else hs_listed[tail].next = taken;
                tail = taken;
            }
            hs_listed[tail].next = HS_LIST_END;
        }
    }
    return head;
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= hs_resolution || texel.y >= hs_resolution) return;
    uint t = uint(texel.y) * uint(hs_resolution) + uint(texel.x);
    uint listed = hs_list_heads[2u * t + 1u];
    uint inserted = 0u;
    for (uint i = hs_sort_list(hs_list_heads[2u * t], listed); i != HS_LIST_END && inserted < listed; i = hs_listed[i].next) {
        hs_insert_fragment(hs_listed[i].depth, hs_listed[i].b);
        ++inserted;
    }
    for (int layer = 0; layer < HS_NODES / 2; ++layer) {
        vec4 v = vec4(0.0);
        if (hs_node_count > 0) {
            int first = min(2 * layer, hs_node_count - 1), second = min(2 * layer + 1, hs_node_count - 1);
            v = vec4(hs_node_depth[first], hs_node_omega[first], hs_node_depth[second], hs_node_omega[second]);
        }
        imageStore(hs_nodes_image, ivec3(texel, layer), v);
    }
    int probed = 0;
    for (int step = 0; step < hs_probe_steps; ++step) ++probed;
    if (inserted != listed || probed != hs_probe_steps) atomicOr(hs_list_status, 1u);
}
