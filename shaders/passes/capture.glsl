// Fragment capture: every fragment's texel, depth, alpha and segment (gl_PrimitiveID) appended to a
// buffer, so that CPU maps can be built from exactly the fragments GL rasterised.
layout(std430, binding = 0) buffer hs_capture_buffer {
    uint hs_captured;
    uint hs_capture_pad[3];
    uvec4 hs_capture[];
};
uniform int hs_resolution;

void main() {
    uint i = atomicAdd(hs_captured, 1u);
    if (i < uint(hs_capture.length()))
        hs_capture[i] = uvec4(uint(gl_FragCoord.y) * uint(hs_resolution) + uint(gl_FragCoord.x), floatBitsToUint(hs_fragment_depth()),
                              floatBitsToUint(hs_fragment_alpha()), uint(gl_PrimitiveID));
}
