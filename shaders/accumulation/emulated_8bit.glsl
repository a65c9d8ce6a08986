// Emulated 8-bit accumulation (Kim & Neumann 2001): RGBA8 targets with additive blending. The output
// b / kappa is converted to unorm8 and the blend saturates; a stored value v (read back in [0, 1])
// stands for the optical depth kappa * v, with exp(-kappa) = 2^-8.
const float HS_KAPPA = 8.0 * 0.69314718055994531;
float hs_encode(float optical_depth) { return clamp(optical_depth / HS_KAPPA, 0.0, 1.0); }
float hs_decode(float stored) { return HS_KAPPA * stored; }
