// Reconstruction by hair count (Unreal Engine's HairStrands deep shadows), after interpolation's
// snippet: T = A^max(0, count - 1) with count = optical depth over one hair's, that is, the
// interpolated optical depth less one hair's (0 where the count starts from zero). Mirrors
// hairshadow::hair_count.
uniform float hs_hair_optical_depth;

float hs_optical_depth(hs_layer_position p) { return max(hs_interpolate(p) - hs_hair_optical_depth, 0.0); }
