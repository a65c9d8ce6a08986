// Density clustering, pass 1 (Mertens et al. 2004, section 3.3): one k-means iteration from K centres
// spread over the texel's depth range. Each fragment adds its weight b = -ln(1 - alpha) (targets
// [0, HS_STATE_TARGETS)) and b * depth (the next HS_STATE_TARGETS) to the cluster of its nearest
// centre, by additive blending into RGBA32F.
layout(location = 0) out vec4 hs_cluster_out[2 * HS_STATE_TARGETS];

void main() {
    vec4 range = texelFetch(hs_range_map, ivec2(gl_FragCoord.xy), 0);
    float centre[HS_LAYERS], unused[HS_LAYERS];
    for (int j = 0; j < HS_LAYERS; ++j) {
        centre[j] = hs_initial_centre(range, j);
        unused[j] = 0.0;
    }
    int cluster = hs_nearest_cluster(centre, unused, true, hs_fragment_depth());
    float b = hs_fragment_optical_depth();
    for (int t = 0; t < HS_STATE_TARGETS; ++t) {
        vec4 weight = vec4(0.0);
        if (cluster / 4 == t) weight[cluster % 4] = b;
        hs_cluster_out[t] = weight;
        hs_cluster_out[HS_STATE_TARGETS + t] = weight * hs_fragment_depth();
    }
}
