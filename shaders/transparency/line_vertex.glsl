// Transparent hair, vertex stage: each strand point in clip space with its colour, the ambient term
// plus every light's radiance (render/hair_colour).
layout(location = 0) in vec3 hs_position;
layout(std430, binding = 2) readonly buffer hs_hair_colours_buffer { vec4 hs_hair_colours[]; };
uniform mat4 hs_camera_view_projection;
uniform vec3 hs_hair_ambient_colour;
uniform int hs_light_count;
uniform int hs_point_count;
invariant gl_Position; // every pass must see the same fragments at the same depths
out vec3 hs_point_colour;

void main() {
    gl_Position = hs_camera_view_projection * vec4(hs_position, 1.0);
    hs_point_colour = hs_hair_ambient_colour;
    for (int k = 0; k < hs_light_count; ++k) hs_point_colour += hs_hair_colours[k * hs_point_count + gl_VertexID].rgb;
}
