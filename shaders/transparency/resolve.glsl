// Transparent hair over the opaque image (full screen): one mode of HS_OCCUPANCY_ORDER,
// HS_WEIGHTED_AVERAGE and HS_EXACT, each as hairshadow::blend_fragments composes it.
uniform sampler2D hs_base;  // the mesh and background, linear
uniform sampler2D hs_sum;   // the blend pass's first target
uniform sampler2D hs_total; // its second (red), unused by HS_EXACT
layout(location = 0) out vec4 hs_out;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 base = texelFetch(hs_base, p, 0).rgb;
    vec4 sum = texelFetch(hs_sum, p, 0);
    float total = texelFetch(hs_total, p, 0).r;
#if defined(HS_OCCUPANCY_ORDER)
    // The alpha correction of section 3.4: the hair's colour rescaled so that its alpha is the exact
    // Lambda = 1 - prod(1 - alpha_i) = 1 - exp(-sum of -ln(1 - alpha_i)).
    if (sum.a > 0.0) {
        float lambda = 1.0 - exp(-total);
        base = sum.rgb * (lambda / sum.a) + (1.0 - lambda) * base;
    }
#elif defined(HS_WEIGHTED_AVERAGE)
    // The average colour, and the average alpha applied as often as there are fragments.
    if (sum.a > 0.0) {
        float behind = pow(1.0 - sum.a / total, total);
        base = sum.rgb / sum.a * (1.0 - behind) + behind * base;
    }
#elif defined(HS_EXACT)
    base = sum.rgb + sum.a * base; // what the peeled layers let through of the base
#endif
    hs_out = vec4(base, 1.0);
}
