// Hair, vertex stage: Kajiya-Kay shading at each strand point (render/hair_shading); lines
// interpolate the colour.
layout(location = 0) in vec3 hs_position;
layout(location = 1) in vec3 hs_tangent;
uniform mat4 hs_camera_view_projection;
invariant gl_Position; // the same depth in every light's pass (GL_LEQUAL)
out vec3 hs_colour;

void main() {
    hs_colour = hs_hair_radiance(hs_position, hs_tangent);
    gl_Position = hs_camera_view_projection * vec4(hs_position, 1.0);
}
