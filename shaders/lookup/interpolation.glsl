// float hs_transmittance(vec3 world_pos) for interpolated methods (opacity shadow maps, deep opacity
// maps, range opacity maps): any user shader can call it. Outside the map the light is unshadowed.
uniform mat4 hs_lookup_view_projection;
uniform mat4 hs_lookup_view;
uniform float hs_lookup_near;
uniform float hs_lookup_far;
uniform int hs_lookup_resolution;
uniform sampler2D hs_range_texture;

float hs_transmittance(vec3 world_pos) {
    vec4 clip = hs_lookup_view_projection * vec4(world_pos, 1.0);
    vec2 window = (clip.xy / clip.w + 1.0) * (0.5 * float(hs_lookup_resolution));
    if (!(clip.w > 0.0) || any(lessThan(window, vec2(0.0))) || any(greaterThanEqual(window, vec2(float(hs_lookup_resolution)))))
        return 1.0;
    hs_lookup_texel = ivec2(window);
    float depth = (-(hs_lookup_view * vec4(world_pos, 1.0)).z - hs_lookup_near) / (hs_lookup_far - hs_lookup_near);
    vec4 range = texelFetch(hs_range_texture, hs_lookup_texel, 0);
    if (range.x > range.w) return 1.0; // no fragment in this texel
    return exp(-hs_interpolate(hs_locate_from(hs_lookup_texel, range, depth)));
}
