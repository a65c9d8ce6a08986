// Transparent hair, vertex stage: each strand point in clip space with its colour (render/hair_colour).
layout(location = 0) in vec3 hs_position;
layout(std430, binding = 2) readonly buffer hs_hair_colours_buffer { vec4 hs_hair_colours[]; };
uniform mat4 hs_camera_view_projection;
out vec3 hs_point_colour;

void main() {
    gl_Position = hs_camera_view_projection * vec4(hs_position, 1.0);
    hs_point_colour = hs_hair_colours[gl_VertexID].rgb;
}
