// The opaque mesh's 1/w at each pixel centre (the nearest surface under MAX blending, 0 where there
// is none), which hides the hair behind it as hairshadow::collect_camera_fragments does.
layout(location = 0) out float hs_inv_w_out;
void main() { hs_inv_w_out = gl_FragCoord.w; }
