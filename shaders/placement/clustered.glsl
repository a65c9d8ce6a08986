// Density clustering's bins (Mertens et al. 2004, sections 3.2-3.3). A texel's state is K cluster
// means and standard deviations (sigma < 0: an empty cluster); bin j spans mean_j +- sqrt(3) sigma_j
// and overlapping neighbours meet at the midpoint of their overlap. Mirrors hairshadow::clustered,
// operation for operation (`precise` keeps the compiler from fusing them).
const float HS_BIN_HALF_WIDTH = 1.7320508;

struct hs_bin {
    float lo;
    float hi;
    bool empty;
};

// Initial k-means centre j: the middle of the j-th of K equal parts of [nearest, furthest].
float hs_initial_centre(vec4 range, int j) {
    precise float width = (range.w - range.x) * (float(j) + 0.5);
    precise float centre = range.x + hs_div_rn(width, float(HS_LAYERS));
    return centre;
}

// The nearest centre (the first on ties) among non-empty clusters, or among all when `all` is set.
int hs_nearest_cluster(float centre[HS_LAYERS], float sigma[HS_LAYERS], bool all, float depth) {
    int best = -1;
    float best_distance = 0.0;
    for (int j = 0; j < HS_LAYERS; ++j) {
        if (!all && sigma[j] < 0.0) continue;
        float d = abs(depth - centre[j]);
        if (best < 0 || d < best_distance) {
            best = j;
            best_distance = d;
        }
    }
    return max(best, 0);
}

void hs_cluster_bins(float mean[HS_LAYERS], float sigma[HS_LAYERS], out hs_bin bins[HS_LAYERS]) {
    int previous = -1;
    for (int j = 0; j < HS_LAYERS; ++j) {
        precise float half_width = HS_BIN_HALF_WIDTH * max(sigma[j], 0.0);
        precise float lo = mean[j] - half_width;
        precise float hi = mean[j] + half_width;
        bins[j] = hs_bin(lo, hi, sigma[j] < 0.0);
        if (bins[j].empty) continue;
        if (previous >= 0 && bins[previous].hi > bins[j].lo) {
            precise float mid = 0.5 * (bins[previous].hi + bins[j].lo);
            mid = clamp(mid, bins[previous].lo, max(bins[previous].lo, bins[j].hi));
            bins[previous].hi = mid;
            bins[j].lo = mid;
            bins[j].hi = max(bins[j].hi, mid);
        }
        previous = j;
    }
}

// The bin holding `depth`, or else the non-empty cluster with the nearest mean.
int hs_assign(float mean[HS_LAYERS], float sigma[HS_LAYERS], float depth) {
    hs_bin bins[HS_LAYERS];
    hs_cluster_bins(mean, sigma, bins);
    for (int j = 0; j < HS_LAYERS; ++j) {
        hs_bin b = bins[j];
        if (!b.empty && depth >= b.lo && (depth < b.hi || (b.lo == b.hi && depth == b.lo))) return j;
    }
    return hs_nearest_cluster(mean, sigma, false, depth);
}

// Inside bin j: (j, fraction); between bins: the end of the bin before; in front of all: -1.
hs_layer_position hs_locate(float mean[HS_LAYERS], float sigma[HS_LAYERS], float depth) {
    hs_bin bins[HS_LAYERS];
    hs_cluster_bins(mean, sigma, bins);
    hs_layer_position p = hs_layer_position(-1, 0.0);
    for (int j = 0; j < HS_LAYERS; ++j) {
        hs_bin b = bins[j];
        if (b.empty) continue;
        if (!(depth > b.lo)) break;
        if (depth >= b.hi) {
            p = hs_layer_position(j, 1.0);
            continue;
        }
        return hs_layer_position(j, hs_div_rn(depth - b.lo, b.hi - b.lo));
    }
    return p;
}
