// Hair, vertex stage: Kajiya-Kay shading at each strand point (as hairshadow::shade_hair_points),
// the light scaled by its visibility; lines interpolate the colour.
layout(location = 0) in vec3 hs_position;
layout(location = 1) in vec3 hs_tangent;
uniform mat4 hs_camera_view_projection;
invariant gl_Position; // the same depth in every light's pass (GL_LEQUAL)
uniform vec3 hs_eye;
uniform vec3 hs_hair_colour;
uniform vec3 hs_hair_specular;
uniform float hs_hair_shininess;
uniform float hs_hair_ambient;
out vec3 hs_colour;

void main() {
    vec3 l = hs_to_light(hs_position), e = normalize(hs_eye - hs_position);
    float tl = dot(hs_tangent, l), te = dot(hs_tangent, e);
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl)), sin_te = sqrt(max(0.0, 1.0 - te * te));
    vec3 reflected = hs_hair_colour * sin_tl + hs_hair_specular * pow(max(0.0, sin_tl * sin_te - tl * te), hs_hair_shininess);
    hs_colour = hs_ambient_weight * hs_hair_ambient * hs_hair_colour + hs_light_colour * hs_light_visibility(hs_position) * reflected;
    gl_Position = hs_camera_view_projection * vec4(hs_position, 1.0);
}
