// float hs_transmittance(vec3 world_pos) for occupancy maps: any user shader can call it after the
// placement, accumulation and reconstruction snippets. Outside the map the light is unshadowed.
uniform mat4 hs_lookup_view_projection;
uniform mat4 hs_lookup_view;
uniform float hs_lookup_near;
uniform float hs_lookup_far;
uniform int hs_lookup_resolution;
uniform sampler2D hs_range_texture;
uniform usampler2D hs_bits_texture[HS_BIT_TARGETS];
uniform sampler2D hs_slabs_texture[HS_SLAB_TARGETS];

float hs_transmittance(vec3 world_pos) {
    vec4 clip = hs_lookup_view_projection * vec4(world_pos, 1.0);
    vec2 window = (clip.xy / clip.w + 1.0) * (0.5 * float(hs_lookup_resolution));
    if (!(clip.w > 0.0) || any(lessThan(window, vec2(0.0))) || any(greaterThanEqual(window, vec2(float(hs_lookup_resolution)))))
        return 1.0;
    ivec2 texel = ivec2(window);
    float depth = (-(hs_lookup_view * vec4(world_pos, 1.0)).z - hs_lookup_near) / (hs_lookup_far - hs_lookup_near);
    vec4 range = texelFetch(hs_range_texture, texel, 0);
    if (range.x > range.w) return 1.0; // no fragment in this texel
    uint bits[HS_WORDS];
    for (int w = 0; w < HS_WORDS; ++w) bits[w] = texelFetch(hs_bits_texture[w / 4], texel, 0)[w % 4];
    float slabs[HS_SLABS];
    for (int s = 0; s < HS_SLABS; ++s) slabs[s] = texelFetch(hs_slabs_texture[s / 4], texel, 0)[s % 4];
    return exp(-hs_occupancy_optical_depth(hs_locate_from(texel, range, depth), bits, slabs));
}
