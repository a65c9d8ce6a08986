// Kajiya-Kay radiance of a strand point towards the eye from one light, scaled by the light's
// visibility there (as hairshadow::shade_hair_points), plus the ambient term in the first pass.
uniform vec3 hs_eye;
uniform vec3 hs_hair_colour;
uniform vec3 hs_hair_specular;
uniform float hs_hair_shininess;
uniform float hs_hair_ambient;

vec3 hs_hair_radiance(vec3 position, vec3 tangent) {
    vec3 l = hs_to_light(position), e = normalize(hs_eye - position);
    float tl = dot(tangent, l), te = dot(tangent, e);
    float sin_tl = sqrt(max(0.0, 1.0 - tl * tl)), sin_te = sqrt(max(0.0, 1.0 - te * te));
    vec3 reflected = hs_hair_colour * sin_tl + hs_hair_specular * pow(max(0.0, sin_tl * sin_te - tl * te), hs_hair_shininess);
    return hs_ambient_weight * hs_hair_ambient * hs_hair_colour + hs_light_colour * hs_light_visibility(position) * reflected;
}
