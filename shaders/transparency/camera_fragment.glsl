// A hair fragment seen from the camera, as hairshadow::collect_camera_fragments makes it: the pixel
// centre's coverage by the line (the distance to the segment against hs_line_reach), 1/w and colour
// interpolated along the segment, alpha = coverage x opacity, hidden where the mesh is nearer. Also
// hs_fragment_depth() and hs_fragment_optical_depth(), so that the shadow maps' passes build
// occupancy maps from the camera's fragments unchanged.
flat in vec2 hs_line_a;
flat in vec2 hs_line_b;
flat in vec2 hs_line_inv_w;
flat in vec3 hs_line_colour_a;
flat in vec3 hs_line_colour_b;
uniform float hs_line_reach;
uniform float hs_hair_opacity;
uniform float hs_camera_near;
uniform float hs_camera_far;
uniform sampler2D hs_surface_inv_w; // the mesh's 1/w (render/mesh_inv_w)

struct hs_camera_fragment {
    bool visible;
    float depth; // view distance, 0 at the near plane and 1 at the far one
    float alpha;
    vec3 colour;
};

hs_camera_fragment hs_this_fragment() {
    vec2 p = gl_FragCoord.xy, d = hs_line_b - hs_line_a;
    float length2 = dot(d, d);
    float t = length2 > 0.0 ? clamp(dot(p - hs_line_a, d) / length2, 0.0, 1.0) : 0.0;
    float coverage = clamp(hs_line_reach - length(p - (hs_line_a + t * d)), 0.0, 1.0);
    // precise: every pass, and both halves of a depth-peeling pass, must agree on the depth.
    precise float inv_w = hs_line_inv_w.x + t * (hs_line_inv_w.y - hs_line_inv_w.x);
    precise float depth = (1.0 / inv_w - hs_camera_near) / (hs_camera_far - hs_camera_near);
    hs_camera_fragment f;
    f.visible = coverage > 0.0 && inv_w > texelFetch(hs_surface_inv_w, ivec2(p), 0).r;
    f.depth = depth;
    f.alpha = min(coverage * hs_hair_opacity, HS_ALPHA_MAX);
    f.colour = hs_line_colour_a + t * (hs_line_colour_b - hs_line_colour_a);
    return f;
}

// Discards the fragments that are not drawn.
float hs_fragment_depth() {
    hs_camera_fragment f = hs_this_fragment();
    if (!f.visible) discard;
    return f.depth;
}
float hs_fragment_optical_depth() { return -log(1.0 - hs_this_fragment().alpha); }
