// Vertex stage of every light-space pass: clip position, linear depth and the strand's attributes.
// The varyings are interpolated perspective-correctly along each line, as the CPU rasteriser does.
layout(location = 0) in vec3 hs_position;
layout(location = 1) in float hs_thickness;
layout(location = 2) in float hs_opacity;

uniform mat4 hs_view_projection;
uniform mat4 hs_view;
uniform float hs_near;   // distance of the near plane from the light
uniform float hs_far;    // distance of the far plane

out float hs_v_depth;
out float hs_v_thickness;
out float hs_v_opacity;

void main() {
    gl_Position = hs_view_projection * vec4(hs_position, 1.0);
    float distance_from_light = -(hs_view * vec4(hs_position, 1.0)).z;
    hs_v_depth = (distance_from_light - hs_near) / (hs_far - hs_near);
    hs_v_thickness = hs_thickness;
    hs_v_opacity = hs_opacity;
}
