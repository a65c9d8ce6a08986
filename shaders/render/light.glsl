// One light of a shaded render (multi-pass: one pass per light, added by blending): its colour and
// direction, and the opaque mesh's depth shadow map seen from it (linear depth, R32F), compared
// with a bias as hairshadow::depth_shadow_map does. hs_transmittance comes from the light's method.
uniform vec3 hs_light_colour;
uniform vec3 hs_light_position;  // point and spot lights
uniform vec3 hs_light_direction; // directional lights: the direction the light travels
uniform bool hs_light_directional;
uniform float hs_light_cos_cone; // spot lights: cos of the half angle; -2 for the others
uniform float hs_ambient_weight; // 1 in the first pass, 0 after
uniform sampler2D hs_mesh_depth;
uniform float hs_mesh_bias;

vec3 hs_to_light(vec3 p) { return hs_light_directional ? -normalize(hs_light_direction) : normalize(hs_light_position - p); }

// 1 in front of the mesh from the light (or outside the map), else 0. Uses the look-up's light
// uniforms (lookup/light.glsl), which every method's look-up declares.
float hs_mesh_visibility(vec3 p) {
    vec4 clip = hs_lookup_view_projection * vec4(p, 1.0);
    vec2 window = (clip.xy / clip.w + 1.0) * (0.5 * float(hs_lookup_resolution));
    if (!(clip.w > 0.0) || any(lessThan(window, vec2(0.0))) || any(greaterThanEqual(window, vec2(float(hs_lookup_resolution))))) return 1.0;
    float depth = (-(hs_lookup_view * vec4(p, 1.0)).z - hs_lookup_near) / (hs_lookup_far - hs_lookup_near);
    return depth <= texelFetch(hs_mesh_depth, ivec2(window), 0).r + hs_mesh_bias ? 1.0 : 0.0;
}

float hs_spot_cone(vec3 p) {
    vec3 d = p - hs_light_position;
    return dot(d, hs_light_direction) >= hs_light_cos_cone * length(d) * length(hs_light_direction) ? 1.0 : 0.0;
}

float hs_light_visibility(vec3 p) { return hs_transmittance(p) * hs_mesh_visibility(p) * hs_spot_cone(p); }
