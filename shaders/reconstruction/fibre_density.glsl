// Approximate deep shadow maps (AMD TressFX, ComputeShadowAttenuation): a point d world units behind
// its texel's first fragment lies behind n = d / hs_fibre_step fibres, at least 1 once d > 1e-5 and at
// most hs_max_fibres (the largest float where there is no cap: TressFX counts them all), each of
// optical depth hs_fibre_optical_depth (and never within four float steps of a depth near 1 of the
// first fragment). HS_MEASURED_DENSITY takes the density from the texel's own fragments: their count
// over their span (n - 1 gaps), each with their mean optical depth, and all of them behind the last.
// Mirrors hairshadow::fibre_density; the range map and the light's frustum are lookup/light's.
uniform float hs_fibre_step;
uniform float hs_fibre_optical_depth;
uniform float hs_max_fibres;
#ifdef HS_MEASURED_DENSITY
uniform sampler2D hs_density_texture; // the texel's summed optical depth (r) and fragment count (g)
#endif

// The plain form, over the texel's fetched values (a port's entry point, docs/texel_layouts.md):
// `sums` is the density texel (r: summed optical depth, g: fragment count; unread without
// HS_MEASURED_DENSITY), `range` the range map's texel.
float hs_fibres_optical_depth_of(vec2 sums, vec4 range, float depth) {
    precise float behind = (depth - range.x) * (hs_lookup_far - hs_lookup_near);
    if (!(behind > 1e-5) || !(depth - range.x > 2.5e-7)) return 0.0;
#ifdef HS_MEASURED_DENSITY
    if (!(sums.g > 0.0)) return 0.0;
    precise float span = range.w - range.x;
    precise float fibres = span > 0.0 && depth <= range.w ? clamp((depth - range.x) / span * (sums.g - 1.0), 1.0, sums.g) : sums.g;
    return fibres * (sums.r / sums.g);
#else
    return clamp(behind / hs_fibre_step, 1.0, hs_max_fibres) * hs_fibre_optical_depth;
#endif
}

float hs_fibres_optical_depth(ivec2 texel, vec4 range, float depth) {
#ifdef HS_MEASURED_DENSITY
    vec2 sums = texelFetch(hs_density_texture, texel, 0).rg;
#else
    vec2 sums = vec2(0.0);
#endif
    return hs_fibres_optical_depth_of(sums, range, depth);
}

float hs_transmittance(vec3 world_pos) {
    ivec2 texel;
    float depth;
    vec4 range;
    if (!hs_lookup_locate(world_pos, texel, depth, range)) return 1.0;
    return exp(-hs_fibres_optical_depth(texel, range, depth));
}
