// Hair colours for transparent hair: each strand point's radiance from one light (render/hair_shading),
// nothing rasterised, written to that light's slice of a storage buffer (light k's radiance of point
// i at k * hs_point_count + i). Written, not added: a vertex shader may run more than once per vertex.
layout(location = 0) in vec3 hs_position;
layout(location = 1) in vec3 hs_tangent;
layout(std430, binding = 2) writeonly buffer hs_hair_colours_buffer { vec4 hs_hair_colours[]; };
uniform int hs_light_index;
uniform int hs_point_count;

void main() {
    hs_hair_colours[hs_light_index * hs_point_count + gl_VertexID] = vec4(hs_hair_radiance(hs_position, hs_tangent), 0.0);
    gl_Position = vec4(0.0);
}
