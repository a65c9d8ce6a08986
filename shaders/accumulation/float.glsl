// Float accumulation: optical depths are written as they are and summed by additive blending into
// RGBA32F targets.
float hs_encode(float optical_depth) { return optical_depth; }
float hs_decode(float stored) { return stored; }
