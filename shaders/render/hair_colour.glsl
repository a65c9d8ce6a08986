// Hair colours for transparent hair: each strand point's radiance from one light (render/hair_shading)
// added to its entry of a storage buffer, one light's pass at a time, nothing rasterised. The
// buffer starts at the ambient term, so that a scene without lights still shows it.
layout(location = 0) in vec3 hs_position;
layout(location = 1) in vec3 hs_tangent;
layout(std430, binding = 2) buffer hs_hair_colours_buffer { vec4 hs_hair_colours[]; };

void main() {
    hs_hair_colours[gl_VertexID] += vec4(hs_hair_radiance(hs_position, hs_tangent), 0.0);
    gl_Position = vec4(0.0);
}
