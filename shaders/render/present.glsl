// Shows a linear-RGB image on an 8-bit framebuffer: the sRGB encoding of hairshadow::image::encode.
uniform sampler2D hs_linear_image;
layout(location = 0) out vec4 hs_out;
void main() {
    vec3 v = clamp(texelFetch(hs_linear_image, ivec2(gl_FragCoord.xy), 0).rgb, 0.0, 1.0);
    vec3 s = mix(1.055 * pow(v, vec3(1.0 / 2.4)) - 0.055, 12.92 * v, lessThanEqual(v, vec3(0.0031308)));
    hs_out = vec4(s, 1.0);
}
