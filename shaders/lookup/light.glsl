// Where a world point falls in the light's maps, shared by every method's hs_transmittance: its
// texel, its linear depth and the texel's depth range. False outside the map or where the texel
// holds no fragment: there the light is unshadowed. The range map is placement/common's.
uniform mat4 hs_lookup_view_projection;
uniform mat4 hs_lookup_view;
uniform float hs_lookup_near;
uniform float hs_lookup_far;
uniform int hs_lookup_resolution;

bool hs_lookup_locate(vec3 world_pos, out ivec2 texel, out float depth, out vec4 range) {
    vec4 clip = hs_lookup_view_projection * vec4(world_pos, 1.0);
    vec2 window = (clip.xy / clip.w + 1.0) * (0.5 * float(hs_lookup_resolution));
    texel = ivec2(0);
    depth = 0.0;
    range = vec4(0.0);
    if (!(clip.w > 0.0) || any(lessThan(window, vec2(0.0))) || any(greaterThanEqual(window, vec2(float(hs_lookup_resolution)))))
        return false;
    texel = ivec2(window);
    depth = (-(hs_lookup_view * vec4(world_pos, 1.0)).z - hs_lookup_near) / (hs_lookup_far - hs_lookup_near);
    range = texelFetch(hs_range_map, texel, 0);
    return range.x <= range.w;
}
