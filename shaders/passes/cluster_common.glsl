// Density clustering's means from pass 1's sums: sum / weight, or the initial centre (and an empty
// cluster, sigma -1) where no fragment chose it; non-empty clusters start with sigma 0.
uniform sampler2DArray hs_cluster_sums; // weights, then weighted depths

void hs_cluster_means(ivec2 texel, vec4 range, out float mean[HS_LAYERS], out float sigma[HS_LAYERS]) {
    for (int j = 0; j < HS_LAYERS; ++j) {
        float weight = texelFetch(hs_cluster_sums, ivec3(texel, j / 4), 0)[j % 4];
        float sum = texelFetch(hs_cluster_sums, ivec3(texel, HS_STATE_TARGETS + j / 4), 0)[j % 4];
        mean[j] = weight > 0.0 ? sum / weight : hs_initial_centre(range, j);
        sigma[j] = weight > 0.0 ? 0.0 : -1.0;
    }
}
