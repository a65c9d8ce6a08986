// Adaptive volumetric shadow maps (Salvi et al. 2010), mirroring hairshadow::adaptive_nodes
// (reconstruction/adaptive_nodes.hpp): a texel's fragments inserted in (depth, optical depth) order,
// each a vertical step of two nodes, and while more than HS_NODES nodes remain, the inner node whose
// removal changes the area under T least removed. exp(-omega) and the areas in the CPU's float
// operations (precise: no fused multiply-adds), so that GL chooses the same nodes, bit for bit.

float hs_transmittance_of(float omega) {
    if (!(omega > 0.0)) return 1.0;
    if (!(omega < 87.3)) return 0.0;
    precise float scaled = omega * 1.44269502;
    float k = floor(scaled + 0.5);
    precise float r = (omega - k * 0.693145752) - k * 1.42860677e-6;
    precise float p = -0.000198412701;
    const float c[7] = float[7](0.00138888892, -0.00833333377, 0.0416666679, -0.166666672, 0.5, -1.0, 1.0);
    for (int i = 0; i < 7; ++i) p = c[i] + r * p;
    precise float t = p * uintBitsToFloat(uint(127 - int(k)) << 23);
    return t;
}

float hs_removal_area(float d0, float t0, float d1, float t1, float d2, float t2) {
    precise float a = (d1 - d0) * (t2 - t0);
    precise float b = (d2 - d0) * (t1 - t0);
    precise float difference = a - b;
    return abs(difference);
}

// The builder's nodes: depth, optical depth in front, transmittance.
const int HS_NODE_CAPACITY = HS_NODES + 2;
float hs_node_depth[HS_NODE_CAPACITY];
float hs_node_omega[HS_NODE_CAPACITY];
float hs_node_t[HS_NODE_CAPACITY];
int hs_node_count = 0;
float hs_node_total = 0.0;

void hs_push_node(float depth, float omega) {
    hs_node_depth[hs_node_count] = depth;
    hs_node_omega[hs_node_count] = omega;
    hs_node_t[hs_node_count] = hs_transmittance_of(omega);
    ++hs_node_count;
}
// The loops run to the arrays' size, not the node count, so that compilers unroll them (and GL
// implementations that bound a shader's loop steps count none of them).
int hs_least_area() {
    int best = 1;
    float best_area = hs_removal_area(hs_node_depth[0], hs_node_t[0], hs_node_depth[1], hs_node_t[1], hs_node_depth[2], hs_node_t[2]);
    for (int i = 2; i < HS_NODE_CAPACITY - 1; ++i) {
        if (i >= hs_node_count - 1) break;
        float a = hs_removal_area(hs_node_depth[i - 1], hs_node_t[i - 1], hs_node_depth[i], hs_node_t[i], hs_node_depth[i + 1], hs_node_t[i + 1]);
        if (a < best_area) {
            best = i;
            best_area = a;
        }
    }
    return best;
}
void hs_remove_node(int removed) {
    for (int i = 1; i < HS_NODE_CAPACITY - 1; ++i) {
        if (i >= removed && i < hs_node_count - 1) {
            hs_node_depth[i] = hs_node_depth[i + 1];
            hs_node_omega[i] = hs_node_omega[i + 1];
            hs_node_t[i] = hs_node_t[i + 1];
        }
    }
    --hs_node_count;
}
// Inserts a fragment of optical depth b > 0 behind every one inserted so far.
void hs_insert_fragment(float depth, float b) {
    if (hs_node_count == 0 || hs_node_depth[hs_node_count - 1] != depth || hs_node_omega[hs_node_count - 1] != hs_node_total)
        hs_push_node(depth, hs_node_total);
    precise float total = hs_node_total + b;
    hs_node_total = total;
    hs_push_node(depth, total);
    for (int r = 0; r < 2; ++r) // at most two nodes over
        if (hs_node_count > HS_NODES) hs_remove_node(hs_least_area());
}

// The look-up: T at `depth` from a texel's nodes (unused ones repeat the last): 1 up to the first
// node, linear between nodes, the last node's behind the last.
float hs_nodes_transmittance(float depths[HS_NODES], float omegas[HS_NODES], float depth) {
    if (!(depth > depths[0])) return 1.0;
    int i = 1;
    while (i < HS_NODES && !(depths[i] >= depth)) ++i;
    if (i == HS_NODES) return exp(-omegas[HS_NODES - 1]);
    if (omegas[i - 1] == omegas[i]) return exp(-omegas[i]);
    float ta = hs_transmittance_of(omegas[i - 1]), tb = hs_transmittance_of(omegas[i]);
    float t = (depth - depths[i - 1]) / (depths[i] - depths[i - 1]);
    return max(ta + t * (tb - ta), exp(-omegas[i]));
}
