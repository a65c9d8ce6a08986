// Compute build, step 1 (one invocation per segment): reads the segment's two points from the mesh's
// buffers, clips it to the light's depth range and the guard band, projects and snaps it exactly as
// hairshadow::detail::prepare_segment does (the same operations in the same order, no fused
// multiply-adds; every quotient by hs_div_rn, no double precision), counts it in every tile its box meets, and widens the
// whole map's extent by its ends, as segment_bins does. A long segment (its box over more than
// HS_SHORT_TILES tiles) is counted in the tiles its line reaches (hs_long_tiles) while the capacity set
// aside for long pairs lasts, and goes to the long list past it.
layout(local_size_x = 256) in;
void hs_emit(int x, int y) {} // this pass walks no lines

// The mesh, as gl::hair_mesh::sources() describes it: buffers bound whole, offsets and strides in floats.
layout(std430, binding = 4) readonly buffer hs_position_buffer { float hs_position_data[]; };
layout(std430, binding = 5) readonly buffer hs_thickness_buffer { float hs_thickness_data[]; };
layout(std430, binding = 6) readonly buffer hs_opacity_buffer { float hs_opacity_data[]; };
layout(std430, binding = 7) readonly buffer hs_index_buffer { uint hs_index_data[]; };
uniform uint hs_segment_count;
uniform uint hs_index_first;         // the first segment's first index, in uints
uniform uvec2 hs_position_layout;    // first float, floats from one point to the next
uniform uvec2 hs_thickness_layout;
uniform uvec2 hs_opacity_layout;
uniform bool hs_thickness_constant, hs_opacity_constant;
uniform float hs_thickness_value, hs_opacity_value;

uniform mat4 hs_view_projection;
uniform mat4 hs_view;
uniform float hs_near, hs_far;

const float HS_GUARD_BAND = 1048576.0; // detail::guard_band, 2^20 texels

struct hs_light_point {
    vec2 window;
    float depth;
    float w;
};

// Row i of m (p, 1), each product rounded before the sums, in the order light_space::row sums them.
float hs_row(mat4 m, int i, vec3 p) {
    precise float x = m[0][i] * p.x;
    precise float y = m[1][i] * p.y;
    precise float z = m[2][i] * p.z;
    precise float r = (x + y) + (z + m[3][i]);
    return r;
}
float hs_distance_of(vec3 p) { return -hs_row(hs_view, 2, p); }
hs_light_point hs_project(vec3 p, float distance) {
    float x = hs_row(hs_view_projection, 0, p), y = hs_row(hs_view_projection, 1, p), w = hs_row(hs_view_projection, 3, p);
    precise float half_res = 0.5 * float(hs_resolution);
    precise float wx = (hs_div_rn(x, w) + 1.0) * half_res;
    precise float wy = (hs_div_rn(y, w) + 1.0) * half_res;
    precise float from_near = distance - hs_near;
    precise float span = hs_far - hs_near;
    return hs_light_point(vec2(wx, wy), hs_div_rn(from_near, span), w);
}

vec3 hs_point(uint i) {
    uint at = hs_position_layout.x + i * hs_position_layout.y;
    return vec3(hs_position_data[at], hs_position_data[at + 1u], hs_position_data[at + 2u]);
}
float hs_thickness(uint i) { return hs_thickness_constant ? hs_thickness_value : hs_thickness_data[hs_thickness_layout.x + i * hs_thickness_layout.y]; }
float hs_opacity(uint i) { return hs_opacity_constant ? hs_opacity_value : hs_opacity_data[hs_opacity_layout.x + i * hs_opacity_layout.y]; }

// Window coordinate to sub-pixel fixed point, half away from zero (detail::snap, which takes it
// through double): x = window S is exact (a power of two; |window| <= 2^20), so are its whole part
// and fraction, and the fraction decides.
int hs_snap(float window) {
    precise float x = window * float(HS_S);
    float whole = trunc(x);
    precise float fraction = x - whole;
    return int(whole) + (abs(fraction) >= 0.5 ? (x < 0.0 ? -1 : 1) : 0);
}

// Clipping to f >= 0 (prepare_segment's clip): narrows [s0, s1]; false when nothing is left.
bool hs_clip(float f0, float f1, inout float s0, inout float s1) {
    if (!(f0 >= 0.0 || f1 >= 0.0)) return false;
    precise float d = f0 - f1;
    if (f0 < 0.0) s0 = max(s0, hs_div_rn(f0, d));
    if (f1 < 0.0) s1 = min(s1, hs_div_rn(f0, d));
    return s0 <= s1;
}

bool hs_in_band(hs_light_point p) { return abs(p.window.x) <= HS_GUARD_BAND && abs(p.window.y) <= HS_GUARD_BAND; }

// (1 - s) / w_a + s / w_b, each product rounded on its own (prepare_segment's weights).
float hs_weights(float s, float ia, float ib) {
    precise float wa = (1.0 - s) * ia, wb = s * ib;
    precise float sum = wa + wb;
    return sum;
}
// Window parameter s to the attributes' parameter, perspective-correct (prepare_segment's perspective).
float hs_perspective(float s, float ia, float ib) {
    precise float sb = s * ib;
    return hs_div_rn(sb, hs_weights(s, ia, ib));
}
// A segment's end where it leaves the guard band, at window parameter s (attribute parameter u).
hs_light_point hs_band_end(hs_light_point a0, hs_light_point b0, float s, float u, float ia, float ib) {
    precise vec2 delta = b0.window - a0.window;
    precise vec2 along = s * delta;
    precise vec2 window = a0.window + along;
    // Clamped to the band: a parameter a few ULP off can put the end just past it (prepare_segment).
    return hs_light_point(clamp(window, -HS_GUARD_BAND, HS_GUARD_BAND), hs_lerp_exact(a0.depth, b0.depth, u), hs_div_rn(1.0, hs_weights(s, ia, ib)));
}

// The segment's prepared form; false when nothing of it is left to draw.
bool hs_prepare(vec3 p0, vec3 p1, inout vec4 at, out hs_segment out_segment) {
    out_segment = hs_segment(ivec4(0), vec4(0.0), vec4(0.0));
    float d0 = hs_distance_of(p0), d1 = hs_distance_of(p1);
    float s0 = 0.0, s1 = 1.0;
    precise float n0 = d0 - hs_near, n1 = d1 - hs_near, f0 = hs_far - d0, f1 = hs_far - d1;
    if (!hs_clip(n0, n1, s0, s1) || !hs_clip(f0, f1, s0, s1)) return false;
    hs_light_point a = hs_project(p0, d0), b = hs_project(p1, d1);
    if (s0 > 0.0 || s1 < 1.0) {
        precise vec3 delta = p1 - p0;
        precise vec3 q0 = p0 + delta * s0;
        precise vec3 q1 = p0 + delta * s1;
        at = vec4(hs_lerp_exact(at.x, at.y, s0), hs_lerp_exact(at.x, at.y, s1), hs_lerp_exact(at.z, at.w, s0), hs_lerp_exact(at.z, at.w, s1));
        a = hs_project(q0, hs_distance_of(q0));
        b = hs_project(q1, hs_distance_of(q1));
    }
    if (!(hs_in_band(a) && hs_in_band(b))) {
        float lo_s = 0.0, hi_s = 1.0;
        for (int axis = 0; axis < 2; ++axis) {
            float from = a.window[axis];
            float delta = b.window[axis] - from; // no product to fuse with: no need of precise (which, here, sends glslang into a loop)
            if (isinf(delta) || isnan(delta)) return false; // ends beyond float's range
            for (int side = 0; side < 2; ++side) {
                bool upper = side == 1;
                float limit = upper ? HS_GUARD_BAND : -HS_GUARD_BAND;
                if (delta == 0.0) {
                    if (upper ? from > limit : from < limit) return false;
                    continue;
                }
                float s = hs_div_rn(limit - from, delta);
                if ((delta > 0.0) == upper) hi_s = min(hi_s, s);
                else lo_s = max(lo_s, s);
            }
        }
        if (!(lo_s < hi_s)) return false;
        float ia = hs_div_rn(1.0, a.w), ib = hs_div_rn(1.0, b.w);
        float u_lo = hs_perspective(lo_s, ia, ib), u_hi = hs_perspective(hi_s, ia, ib);
        at = vec4(hs_lerp_exact(at.x, at.y, u_lo), hs_lerp_exact(at.x, at.y, u_hi), hs_lerp_exact(at.z, at.w, u_lo), hs_lerp_exact(at.z, at.w, u_hi));
        hs_light_point a0 = a, b0 = b;
        a = hs_band_end(a0, b0, lo_s, u_lo, ia, ib);
        b = hs_band_end(a0, b0, hi_s, u_hi, ia, ib);
    }
    if (!(hs_in_band(a) && hs_in_band(b) && abs(a.depth) <= 2.0 && abs(b.depth) <= 2.0 && a.w > 0.0 && b.w > 0.0)) return false;
    out_segment = hs_segment(ivec4(hs_snap(a.window.x), hs_snap(a.window.y), hs_snap(b.window.x), hs_snap(b.window.y)),
                             vec4(a.depth, b.depth, hs_div_rn(1.0, a.w), hs_div_rn(1.0, b.w)), at);
    return out_segment.ends.xy != out_segment.ends.zw;
}

// Takes `pairs` words of the hs_long_capacity set aside for long segments' pairs, if that many are left:
// a compare-and-swap loop, so the count never passes the capacity (an atomicAdd could wrap).
uniform uint hs_long_capacity;
bool hs_reserve_long(uint pairs) {
    uint seen = hs_long_reserved;
    for (;;) {
        if (seen > hs_long_capacity || pairs > hs_long_capacity - seen) return false;
        uint was = atomicCompSwap(hs_long_reserved, seen, seen + pairs);
        if (was == seen) return true;
        seen = was;
    }
}

void main() {
    uint i = hs_segment_index();
    if (i >= hs_segment_count) return;
    uint i0 = hs_index_data[hs_index_first + 2u * i], i1 = hs_index_data[hs_index_first + 2u * i + 1u];
    vec4 at = vec4(hs_thickness(i0), hs_thickness(i1), hs_opacity(i0), hs_opacity(i1));
    hs_segment s;
    ivec4 box;
    bool drawn = hs_prepare(hs_point(i0), hs_point(i1), at, s) && hs_segment_box(s.ends, box);
    if (!drawn) s.ends = ivec4(0); // nothing to walk, and no tile
    hs_segments[i] = s;
    if (!drawn) return;
    atomicMin(hs_nearest_bits, hs_ordered(min(s.depth_w.x, s.depth_w.y)));
    atomicMax(hs_furthest_bits, hs_ordered(max(s.depth_w.x, s.depth_w.y)));
    ivec4 tiles = box / HS_TILE;
    if ((tiles.z - tiles.x + 1) * (tiles.w - tiles.y + 1) > HS_SHORT_TILES) {
        uint pairs = hs_long_tiles(s.ends, box, 0, i);
        atomicAdd(hs_long_wanted, pairs);
        if (hs_reserve_long(pairs)) {
            hs_long_tiles(s.ends, box, 1, i);
            hs_binned[hs_long_first + hs_segment_count - 1u - atomicAdd(hs_long_binned, 1u)] = i;
        } else {
            hs_binned[hs_long_first + atomicAdd(hs_long_count, 1u)] = i;
        }
        return;
    }
    for (int ty = tiles.y; ty <= tiles.w; ++ty)
        for (int tx = tiles.x; tx <= tiles.z; ++tx) atomicAdd(hs_tile_counts[ty * hs_tiles_x + tx], 1u);
}
