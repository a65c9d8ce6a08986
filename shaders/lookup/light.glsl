// Where a world point falls in the light's maps, shared by every method's hs_transmittance: its
// texel, its linear depth and the texel's depth range. False outside the map or where the texel
// holds no fragment: there the light is unshadowed. The range map is placement/common's.
// The arithmetic is the CPU query's (light_space::project, map_queries::transmittance), operation
// for operation and `precise` (no fused multiply-add, no reordering), so that the look-up finds the
// CPU's texel and depth; quotients are hs_div_rn's, the CPU's on every GPU (GLSL's own division may be
// 2.5 ULP off, which could move a point lying within a rounding of a texel's edge).
uniform mat4 hs_lookup_view_projection;
uniform mat4 hs_lookup_view;
uniform float hs_lookup_near;
uniform float hs_lookup_far;
uniform int hs_lookup_resolution;
uniform float hs_lookup_depth_bias; // linear depth towards the light (query_options::depth_bias)

// Row i of m * (p, 1), summed as light_space::row sums it: (m0 p.x + m1 p.y) + (m2 p.z + m3).
float hs_lookup_row(mat4 m, int i, vec3 p) {
    precise float r = (m[0][i] * p.x + m[1][i] * p.y) + (m[2][i] * p.z + m[3][i]);
    return r;
}

bool hs_lookup_locate(vec3 world_pos, out ivec2 texel, out float depth, out vec4 range) {
    precise float x = hs_lookup_row(hs_lookup_view_projection, 0, world_pos);
    precise float y = hs_lookup_row(hs_lookup_view_projection, 1, world_pos);
    precise float w = hs_lookup_row(hs_lookup_view_projection, 3, world_pos);
    precise float half_resolution = 0.5 * float(hs_lookup_resolution);
    precise vec2 window = vec2((hs_div_rn(x, w) + 1.0) * half_resolution, (hs_div_rn(y, w) + 1.0) * half_resolution);
    texel = ivec2(0);
    depth = 0.0;
    range = vec4(0.0);
    if (!(w > 0.0) || !(window.x >= 0.0) || !(window.y >= 0.0) || !(window.x < float(hs_lookup_resolution)) ||
        !(window.y < float(hs_lookup_resolution)))
        return false;
    texel = ivec2(window);
    precise float distance = -hs_lookup_row(hs_lookup_view, 2, world_pos);
    precise float biased = hs_div_rn(distance - hs_lookup_near, hs_lookup_far - hs_lookup_near) - hs_lookup_depth_bias;
    depth = biased;
    range = texelFetch(hs_range_map, texel, 0);
    return range.x <= range.w;
}
