// The raster path's list pass: every fragment GL rasterises appended to its texel's list
// (passes/fragment_lists), with no colour written.
uniform int hs_resolution;

void main() { hs_append_fragment(uint(gl_FragCoord.y) * uint(hs_resolution) + uint(gl_FragCoord.x), hs_fragment_depth(), hs_fragment_optical_depth()); }
