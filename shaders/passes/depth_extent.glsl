// The whole map's depth extent, reduced on the GPU from the depth-range map so that no build reads it
// back. With HS_EXTENT_TILES, each work group reduces one 64x64 tile of the range map (16 texels an
// invocation, then the group's 256 partial results) to one texel of hs_extent_output; without, one work group reduces those tiles and writes (nearest, 0, 0, furthest),
// or zero for an empty map (as hairshadow::extent_of), to hs_extent_texel of the range map's extra
// row. Min and max are exact, so the extent equals the CPU's.
layout(local_size_x = 16, local_size_y = 16) in;
uniform sampler2D hs_extent_input; // the range map, or the tiles
uniform ivec2 hs_input_size;       // texels of hs_extent_input to reduce
uniform ivec2 hs_extent_texel;
layout(rgba32f) writeonly uniform image2D hs_extent_output;
shared vec2 hs_partial[256];

vec2 hs_merge(vec2 a, vec4 range) { return vec2(min(a.x, range.x), max(a.y, range.w)); }

void main() {
    uint i = gl_LocalInvocationIndex;
    vec2 e = vec2(3.0e38, -3.0e38);
#ifdef HS_EXTENT_TILES
    // Neighbouring invocations read neighbouring texels; few groups keep the barriers few.
    for (int y = 0; y < 64; y += 16)
        for (int x = 0; x < 64; x += 16) {
            ivec2 texel = ivec2(gl_WorkGroupID.xy) * 64 + ivec2(gl_LocalInvocationID.xy) + ivec2(x, y);
            if (all(lessThan(texel, hs_input_size))) e = hs_merge(e, texelFetch(hs_extent_input, texel, 0));
        }
#else
    for (int y = int(gl_LocalInvocationID.y); y < hs_input_size.y; y += 16)
        for (int x = int(gl_LocalInvocationID.x); x < hs_input_size.x; x += 16) e = hs_merge(e, texelFetch(hs_extent_input, ivec2(x, y), 0));
#endif
    hs_partial[i] = e;
    memoryBarrierShared();
    barrier();
    for (uint half_size = 128u; half_size > 0u; half_size >>= 1) {
        if (i < half_size) hs_partial[i] = hs_merge(hs_partial[i], hs_partial[i + half_size].xxxy);
        memoryBarrierShared();
        barrier();
    }
    if (i != 0u) return;
    vec2 r = hs_partial[0];
#ifdef HS_EXTENT_TILES
    imageStore(hs_extent_output, ivec2(gl_WorkGroupID.xy), vec4(r.x, 0.0, 0.0, r.y));
#else
    imageStore(hs_extent_output, hs_extent_texel, r.x <= r.y ? vec4(r.x, 0.0, 0.0, r.y) : vec4(0.0));
#endif
}
