// Weighted-average blending (Bavoil & Myers 2008), the blend pass: every visible fragment adds
// (alpha x colour, alpha) and a count of 1, unsorted, by additive blending; transparency/resolve
// averages them.
layout(location = 0) out vec4 hs_sum_out;   // rgb: alpha x colour, a: alpha
layout(location = 1) out vec4 hs_total_out; // r: the number of fragments

void main() {
    hs_camera_fragment f = hs_this_fragment();
    if (!f.visible) discard;
    hs_sum_out = vec4(f.alpha * f.colour, f.alpha);
    hs_total_out = vec4(1.0, 0.0, 0.0, 0.0);
}
