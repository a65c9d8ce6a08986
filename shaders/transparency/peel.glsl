// Depth peeling (Everitt 2001), front to back, for exact blending. Each layer takes two draws of
// the hair: the first keeps each pixel's nearest depth beyond the last layer's (MIN blending); the
// second under-blends every fragment at exactly that depth, so that fragments of equal depth (where
// a strand's segments meet) are all blended, in drawing order, none lost. Under-blending keeps
// rgb += T alpha colour and T *= (1 - alpha) in alpha: glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE,
// GL_ZERO, GL_ONE_MINUS_SRC_ALPHA) over a target cleared to (0, 0, 0, 1).
uniform bool hs_find_layer;
uniform sampler2D hs_peeled_depth; // the last layer's depth (-infinity before the first)
uniform sampler2D hs_layer_depth;  // this layer's (the second draw)
layout(location = 0) out vec4 hs_out;

void main() {
    hs_camera_fragment f = hs_this_fragment();
    if (!f.visible) discard;
    ivec2 texel = ivec2(gl_FragCoord.xy);
    if (hs_find_layer) {
        if (!(f.depth > texelFetch(hs_peeled_depth, texel, 0).r)) discard;
        hs_out = vec4(f.depth);
    } else {
        if (f.depth != texelFetch(hs_layer_depth, texel, 0).r) discard;
        hs_out = vec4(f.alpha * f.colour, f.alpha);
    }
}
