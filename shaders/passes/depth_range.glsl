// Depth-range pass (Sintorn & Assarsson 2009, section 3.1): red keeps the nearest fragment under MIN
// blending, alpha the furthest under MAX blending (glBlendEquationSeparate(GL_MIN, GL_MAX)).
out vec4 hs_range_out;

void main() {
    float depth = hs_fragment_depth();
    hs_range_out = vec4(depth, 0.0, 0.0, depth);
}
