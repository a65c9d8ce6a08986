// Opaque mesh, vertex stage: world position and normal for per-pixel shading.
layout(location = 0) in vec3 hs_position;
layout(location = 1) in vec3 hs_normal;
uniform mat4 hs_camera_view_projection;
invariant gl_Position; // the same depth in every light's pass (GL_LEQUAL)
out vec3 hs_world;
out vec3 hs_world_normal;
void main() {
    hs_world = hs_position;
    hs_world_normal = hs_normal;
    gl_Position = hs_camera_view_projection * vec4(hs_position, 1.0);
}
