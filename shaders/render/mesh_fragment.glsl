// Opaque mesh, fragment stage: two-sided Lambert shading (as hairshadow::render_cpu), the light
// scaled by the hair's transmittance and the mesh's own shadow at this pixel.
in vec3 hs_world;
in vec3 hs_world_normal;
uniform vec3 hs_eye;
uniform vec3 hs_mesh_colour;
uniform float hs_mesh_ambient;
layout(location = 0) out vec4 hs_out;
void main() {
    vec3 n = normalize(hs_world_normal);
    if (dot(n, hs_eye - hs_world) < 0.0) n = -n;
    float lit = max(0.0, dot(n, hs_to_light(hs_world))) * hs_light_visibility(hs_world);
    hs_out = vec4(hs_ambient_weight * hs_mesh_ambient * hs_mesh_colour + hs_light_colour * hs_mesh_colour * lit, 1.0);
}
