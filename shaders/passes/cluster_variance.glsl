// Density clustering, pass 2 (Mertens et al. 2004, section 3.3): each fragment adds b and
// b (depth - mean)^2 to its nearest non-empty cluster, for the clusters' standard deviations.
layout(location = 0) out vec4 hs_cluster_out[2 * HS_STATE_TARGETS];

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float mean[HS_LAYERS], sigma[HS_LAYERS];
    hs_cluster_means(texel, texelFetch(hs_range_map, texel, 0), mean, sigma);
    float depth = hs_fragment_depth();
    int cluster = hs_nearest_cluster(mean, sigma, false, depth);
    float b = hs_fragment_optical_depth(), d = depth - mean[cluster];
    for (int t = 0; t < HS_STATE_TARGETS; ++t) {
        vec4 weight = vec4(0.0);
        if (cluster / 4 == t) weight[cluster % 4] = b;
        hs_cluster_out[t] = weight;
        hs_cluster_out[HS_STATE_TARGETS + t] = weight * (d * d);
    }
}
