// Hair, fragment stage: the interpolated colour; multisampling gives the lines their coverage.
in vec3 hs_colour;
layout(location = 0) out vec4 hs_out;
void main() { hs_out = vec4(hs_colour, 1.0); }
