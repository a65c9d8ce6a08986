// The measured fibre density's pass: every fragment adds its optical depth (r) and a count of one (g)
// to its texel, by additive blending into an RG32F target.
layout(location = 0) out vec2 hs_density_out;

void main() { hs_density_out = vec2(hs_fragment_optical_depth(), 1.0); }
