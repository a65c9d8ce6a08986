// Compute build of density clustering (Mertens et al. 2004, section 3.3; one work group per tile, in
// strips of HS_STRIP_ROWS rows so that a strip's sums fit shared memory): three walks of the tile's
// segments per strip. Walk 1 sums each fragment's b and b depth into the cluster of its nearest initial
// centre; walk 2 sums b (depth - mean)^2 into the cluster of its nearest mean; walk 3 adds b to the
// bin placement/clustered assigns it. The k-means sums are hairshadow::clustered's fixed-point integers
// (2^-36) in two 32-bit words, and the means and deviations are taken from them with correctly rounded
// float operations (hs_div_rn, hs_sqrt_rn), so they are the CPU's bit for bit with no double precision
// or 64-bit integers; the histogram is summed as the layers pass sums. Writes the state (means, then
// deviations) and the histogram where the raster passes put them.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0, HS_LAYERS_FORMAT) writeonly uniform image2DArray hs_layers_image;
layout(binding = 1, rgba32f) writeonly uniform image2DArray hs_state_image;

const int HS_STRIP = HS_TILE * HS_STRIP_ROWS; // texels of a strip
shared float hs_mean[HS_STRIP * HS_LAYERS], hs_sigma[HS_STRIP * HS_LAYERS];
ivec2 hs_origin;
int hs_walk_kind;

// A signed fixed-point sum's value over another's, as clustered::set_means takes it: each rounded to
// float, then the quotient correctly rounded.
float hs_sum_quotient(uvec2 numerator, uvec2 denominator) {
    return hs_div_rn(hs_float_of_signed_words(numerator), hs_float_of_signed_words(denominator));
}
// A signed fixed-point sum above zero.
bool hs_positive(uvec2 v) { return (v.y & 0x80000000u) == 0u && (v.x | v.y) != 0u; }

// Initial k-means centre j: the middle of the j-th of K equal parts of [nearest, furthest].
float hs_centre(vec2 range, int j) {
    precise float width = (range.y - range.x) * (float(j) + 0.5);
    precise float centre = range.x + hs_div_rn(width, float(HS_LAYERS));
    return centre;
}

// One emission for the three walks, which differ only in what they read and add: llvmpipe runs every
// side of a branch under lane masks, even on a uniform condition, so three emissions cost three
// (BENCHMARKS.md, "llvmpipe's masked passes"). Walk 1 reads the initial centres where walk 2 reads the
// means: both are in hs_mean, walk 1's deviations 0, so that the nearest of the non-empty clusters is
// the nearest of all (hs_nearest_cluster's `all`).
void hs_emit(int x, int y) {
    uint texel = uint((y - hs_origin.y) * HS_TILE + (x - hs_origin.x));
    float depth, b;
    hs_shade(x, y, depth, b);
    uint state = texel * uint(HS_LAYERS);
    float mean[HS_LAYERS], sigma[HS_LAYERS];
    for (int j = 0; j < HS_LAYERS; ++j) {
        mean[j] = hs_mean[state + uint(j)];
        sigma[j] = hs_sigma[state + uint(j)];
    }
    if (hs_walk_kind == 2) {
        hs_add_sum(texel * uint(HS_SUM_SLOTS) + uint(hs_assign(mean, sigma, depth)), b);
        return;
    }
    uint j = uint(hs_nearest_cluster(mean, sigma, false, depth));
    precise float d = depth - mean[j];
    precise float squared = d * d; // clustered::squared_distance
    hs_add_fixed(texel * uint(HS_SUM_SLOTS) + j, hs_fixed_product(b, 1.0));
    hs_add_fixed(texel * uint(HS_SUM_SLOTS) + uint(HS_LAYERS) + j, hs_fixed_product(b, hs_walk_kind == 0 ? depth : squared));
}

void main() {
    uint tile = gl_WorkGroupID.y * uint(hs_tiles_x) + gl_WorkGroupID.x;
    ivec4 rect = hs_tile_rect(tile);
    uint me = gl_LocalInvocationIndex;
    for (int strip = 0; strip * HS_STRIP_ROWS < HS_TILE; ++strip) {
        hs_origin = ivec2(rect.x, rect.y + strip * HS_STRIP_ROWS);
        ivec4 clip = ivec4(hs_origin, rect.z, min(hs_origin.y + HS_STRIP_ROWS, rect.w));
        bool mine = me < uint(HS_STRIP); // this invocation resolves texel `me` of the strip
        ivec2 texel = hs_origin + ivec2(int(me) % HS_TILE, int(me) / HS_TILE);
        bool inside = mine && texel.x < clip.z && texel.y < clip.w;
        if (mine) {
            vec2 range = inside ? texelFetch(hs_range_map, texel, 0).xw : vec2(0.0);
            for (int j = 0; j < HS_LAYERS; ++j) {
                hs_mean[me * uint(HS_LAYERS) + uint(j)] = hs_centre(range, j);
                hs_sigma[me * uint(HS_LAYERS) + uint(j)] = 0.0;
            }
        }
        for (hs_walk_kind = 0; hs_walk_kind < 3; ++hs_walk_kind) {
            hs_clear_sums();
            barrier();
            if (clip.y < clip.w) hs_walk_tile_rect(tile, clip);
            barrier();
            if (mine) {
                uint sums = me * uint(HS_SUM_SLOTS), state = me * uint(HS_LAYERS);
                for (int j = 0; j < HS_LAYERS; ++j) {
                    uvec2 weight = hs_sum(sums + uint(j)), total = hs_sum(sums + uint(HS_LAYERS + j));
                    bool taken = hs_positive(weight);
                    if (hs_walk_kind == 0) {
                        if (taken) hs_mean[state + uint(j)] = hs_sum_quotient(total, weight); // else the initial centre stays
                        // Selected as bits: a compiler may turn a select of 0.0 and -1.0 into -float(!cond),
                        // which gives -0 where the CPU has +0.
                        hs_sigma[state + uint(j)] = uintBitsToFloat(taken ? 0u : floatBitsToUint(-1.0));
                    } else if (hs_walk_kind == 1) {
                        if (hs_sigma[state + uint(j)] >= 0.0 && taken) hs_sigma[state + uint(j)] = hs_sqrt_rn(hs_sum_quotient(total, weight));
                    }
                }
                if (inside && hs_walk_kind == 1) {
                    for (int t = 0; t < (HS_LAYERS + 3) / 4; ++t) {
                        vec4 m = vec4(0.0), s = vec4(-1.0);
                        for (int c = 0; c < 4 && 4 * t + c < HS_LAYERS; ++c) {
                            m[c] = hs_mean[state + uint(4 * t + c)];
                            // -0 stored as +0, the CPU's zero: llvmpipe makes -0 deviations (a select or a
                            // root rewritten); they compare as +0, so only the stored bits differ.
                            uint bits = floatBitsToUint(hs_sigma[state + uint(4 * t + c)]);
                            s[c] = uintBitsToFloat(bits == 0x80000000u ? 0u : bits);
                        }
                        imageStore(hs_state_image, ivec3(texel, t), m);
                        imageStore(hs_state_image, ivec3(texel, (HS_LAYERS + 3) / 4 + t), s);
                    }
                }
                if (inside && hs_walk_kind == 2) {
                    for (int t = 0; t < (HS_LAYERS + 3) / 4; ++t) {
                        vec4 v = vec4(0.0);
                        for (int c = 0; c < 4 && 4 * t + c < HS_LAYERS; ++c) v[c] = hs_stored(hs_sum(sums + uint(4 * t + c)));
                        imageStore(hs_layers_image, ivec3(texel, t), v);
                    }
                }
            }
            barrier();
        }
    }
}
