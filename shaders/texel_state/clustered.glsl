// Density clustering's per-texel state: the means (array layers [0, HS_STATE_TARGETS)) and standard
// deviations (the next HS_STATE_TARGETS layers) written by passes/cluster_resolve.
uniform sampler2DArray hs_cluster_state;

void hs_load_clusters(ivec2 texel, out float mean[HS_LAYERS], out float sigma[HS_LAYERS]) {
    for (int j = 0; j < HS_LAYERS; ++j) {
        mean[j] = texelFetch(hs_cluster_state, ivec3(texel, j / 4), 0)[j % 4];
        sigma[j] = texelFetch(hs_cluster_state, ivec3(texel, HS_STATE_TARGETS + j / 4), 0)[j % 4];
    }
}
int hs_assign_from(ivec2 texel, vec4 range, float depth) {
    float mean[HS_LAYERS], sigma[HS_LAYERS];
    hs_load_clusters(texel, mean, sigma);
    return hs_assign(mean, sigma, depth);
}
hs_layer_position hs_locate_from(ivec2 texel, vec4 range, float depth) {
    float mean[HS_LAYERS], sigma[HS_LAYERS];
    hs_load_clusters(texel, mean, sigma);
    return hs_locate(mean, sigma, depth);
}
