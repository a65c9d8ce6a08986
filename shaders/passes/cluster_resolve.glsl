// Density clustering's state, one full-screen pass: the means (targets [0, HS_STATE_TARGETS)) and
// standard deviations sqrt(sum b (depth - mean)^2 / sum b) (the next HS_STATE_TARGETS).
uniform sampler2DArray hs_cluster_variance; // weights, then weighted squared distances
layout(location = 0) out vec4 hs_state_out[2 * HS_STATE_TARGETS];

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float mean[HS_LAYERS], sigma[HS_LAYERS];
    hs_cluster_means(texel, texelFetch(hs_range_map, texel, 0), mean, sigma);
    for (int j = 0; j < HS_LAYERS; ++j) {
        float weight = texelFetch(hs_cluster_variance, ivec3(texel, j / 4), 0)[j % 4];
        float sum = texelFetch(hs_cluster_variance, ivec3(texel, HS_STATE_TARGETS + j / 4), 0)[j % 4];
        if (sigma[j] >= 0.0 && weight > 0.0) sigma[j] = sqrt(sum / weight);
    }
    for (int t = 0; t < HS_STATE_TARGETS; ++t) {
        vec4 m = vec4(0.0), s = vec4(-1.0);
        for (int c = 0; c < 4 && 4 * t + c < HS_LAYERS; ++c) {
            m[c] = mean[4 * t + c];
            s[c] = sigma[4 * t + c];
        }
        hs_state_out[t] = m;
        hs_state_out[HS_STATE_TARGETS + t] = s;
    }
}
