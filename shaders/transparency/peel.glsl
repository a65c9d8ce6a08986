// Depth peeling (Everitt 2001), front to back, for exact blending, one draw per layer. A draw
// under-blends every fragment at exactly the current layer's depth into its first target, and keeps
// each pixel's nearest depth beyond that layer in its second, for the next draw. Fragments of equal
// depth (where a strand's segments meet) are all blended, in drawing order, none lost.
// - Under-blending keeps rgb += T alpha colour and T *= (1 - alpha) in alpha: glBlendFuncSeparatei(0,
//   GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA) over a target cleared to (0, 0, 0, 1).
// - The next layer: red under MIN (cleared to infinity), alpha under MAX (cleared to 0) marks the
//   pixels that have one: glBlendEquationSeparatei(1, GL_MIN, GL_MAX).
uniform bool hs_first_layer;       // the first draw: no layer yet, every fragment is beyond
uniform sampler2D hs_layer_depth;  // this layer: red its depth, alpha 1 where the pixel has one
layout(location = 0) out vec4 hs_blend_out;
layout(location = 1) out vec4 hs_next_out;

void main() {
    hs_camera_fragment f = hs_this_fragment();
    if (!f.visible || isnan(f.depth)) discard;
    vec4 layer = texelFetch(hs_layer_depth, ivec2(gl_FragCoord.xy), 0);
    bool has_layer = !hs_first_layer && layer.a > 0.0;
    bool in_layer = has_layer && f.depth == layer.r;
    bool beyond = hs_first_layer || (has_layer && f.depth > layer.r);
    if (!in_layer && !beyond) discard; // peeled already
    hs_blend_out = in_layer ? vec4(f.alpha * f.colour, f.alpha) : vec4(0.0);
    hs_next_out = beyond ? vec4(f.depth, 0.0, 0.0, 1.0) : vec4(uintBitsToFloat(0x7f800000u), 0.0, 0.0, 0.0);
}
