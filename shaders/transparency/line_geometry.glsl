// Transparent hair, geometry stage: each segment as a window rectangle holding every pixel centre its
// anti-aliased line can touch: the segment widened by hs_line_reach (half the line width plus half a
// pixel) and 1/8 pixel more on every side, so that no centre is lost to the corners' snapping to the
// subpixel grid (at least 4 bits, GL_SUBPIXEL_BITS).
// The ends go to the fragment stage flat, which measures each pixel's coverage as
// hairshadow::detail::for_each_line_pixel does; segments with an end behind the camera are dropped there too.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
in vec3 hs_point_colour[];
uniform vec2 hs_viewport;
uniform float hs_line_reach;
flat out vec2 hs_line_a;
flat out vec2 hs_line_b;
flat out vec2 hs_line_inv_w;
flat out vec3 hs_line_colour_a;
flat out vec3 hs_line_colour_b;

void main() {
    vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position;
    if (!(a.w > 1e-6) || !(b.w > 1e-6)) return;
    precise vec2 wa = (a.xy / a.w + 1.0) * 0.5 * hs_viewport, wb = (b.xy / b.w + 1.0) * 0.5 * hs_viewport;
    float len = length(wb - wa);
    vec2 along = (len > 0.0 ? (wb - wa) / len : vec2(1.0, 0.0)) * (hs_line_reach + 0.125);
    vec2 across = vec2(-along.y, along.x);
    vec2 corners[4] = vec2[4](wa - along - across, wa - along + across, wb + along - across, wb + along + across);
    for (int i = 0; i < 4; ++i) {
        hs_line_a = wa;
        hs_line_b = wb;
        precise vec2 inv_w = vec2(1.0 / a.w, 1.0 / b.w);
        hs_line_inv_w = inv_w;
        hs_line_colour_a = hs_point_colour[0];
        hs_line_colour_b = hs_point_colour[1];
        gl_Position = vec4(corners[i] / hs_viewport * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
