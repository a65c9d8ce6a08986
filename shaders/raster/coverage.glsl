// A fragment's alpha: the strand's opacity times the share of the texel its thickness covers, or a
// fixed alpha; clamped below 1 (HS_ALPHA_MAX). Mirrors hairshadow::detail::segment_shader::shade.
in float hs_v_depth;
in float hs_v_thickness;
in float hs_v_opacity;

// The fragment's linear depth from the light, as every pass reads it.
float hs_fragment_depth() { return hs_v_depth; }

uniform bool hs_use_fixed_alpha;
uniform float hs_fixed_alpha;
// World width of a texel at linear depth d: hs_texel_size.x + hs_texel_size.y * d.
uniform vec2 hs_texel_size;
uniform bool hs_depth_weighting;

float hs_fragment_alpha() {
    float alpha;
    if (hs_use_fixed_alpha) {
        alpha = hs_fixed_alpha;
    } else {
        float footprint = hs_texel_size.x + hs_texel_size.y * (hs_depth_weighting ? hs_v_depth : 0.5);
        alpha = hs_v_opacity * min(1.0, hs_v_thickness / footprint);
    }
    return clamp(alpha, 0.0, HS_ALPHA_MAX);
}

// b = -ln(1 - alpha): the fragment's optical depth.
float hs_fragment_optical_depth() { return -log(1.0 - hs_fragment_alpha()); }
