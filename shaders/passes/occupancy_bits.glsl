// Occupancy pass (Sintorn & Assarsson 2009, section 3.1): the bit of the fragment's slice, OR-ed into
// RGBA32UI targets of 128 bits each by glLogicOp(GL_OR).
layout(location = 0) out uvec4 hs_bits_out[HS_BIT_TARGETS];

void main() {
    vec4 range = texelFetch(hs_range_map, ivec2(gl_FragCoord.xy), 0);
    int k = hs_assign_from(ivec2(gl_FragCoord.xy), range, hs_fragment_depth());
    if (k < 0) discard;
    uvec4 word = uvec4(0u);
    word[(k % 128) / 32] = 1u << uint(k % 32);
    for (int t = 0; t < HS_BIT_TARGETS; ++t) hs_bits_out[t] = (k / 128 == t) ? word : uvec4(0u);
}
