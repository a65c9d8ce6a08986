// What every pass of the compute build shares (gl/passes/compute_raster.hpp): the prepared segments and their
// tiles, and the line rule of raster/line_rule.hpp in 32-bit integers, so that a tile's work group
// makes exactly the fragments the CPU rasteriser makes. A pass defines hs_emit(x, y), which the walk
// calls for every fragment of the current segment inside the tile. Everything here is 32-bit: the
// walk in integers, the fragments' parameter, depth and optical depth in float; no program of the
// compute path needs double precision, 64-bit integers or any extension (scripts/validate_shaders.py).

// Coordinates lie within the guard band, |c| <= 2^(20 + bits) sub-pixels, so with at most 9 bits every
// difference and every remainder of the walk below fits a 32-bit int (the CPU's line rule asserts the
// same range, raster/line_rule.hpp).
#if HS_SUBPIXEL_BITS < 1 || HS_SUBPIXEL_BITS > 9
#error "the compute line rule needs 1 <= HS_SUBPIXEL_BITS <= 9"
#endif
const int HS_S = 1 << HS_SUBPIXEL_BITS; // sub-pixel steps per texel
const int HS_H = HS_S / 2;

// A prepared segment (hairshadow::detail::prepared_segment and its segment_attributes): snapped ends,
// linear depth and 1/w at both ends, thickness and opacity at both ends. Both ends equal: nothing to draw.
struct hs_segment {
    ivec4 ends;         // ax, ay, bx, by
    vec4 depth_w;       // depth_a, depth_b, inv_w_a, inv_w_b
    vec4 attributes;    // thickness_a, thickness_b, opacity_a, opacity_b
};
layout(std430, binding = 0) buffer hs_segment_buffer { hs_segment hs_segments[]; };
layout(std430, binding = 1) buffer hs_tile_count_buffer { uint hs_tile_counts[]; };   // per tile; the scatter's cursors
// The whole map's extent as ordered bits (hs_ordered), the number of segment-tile pairs, the long
// segments (below) in the long list and in the tiles' lists, the long pairs granted and wanted, and
// each tile's first pair (tiles + 1 exclusive prefix sums).
layout(std430, binding = 2) buffer hs_tile_offset_buffer {
    uint hs_nearest_bits;
    uint hs_furthest_bits;
    uint hs_pairs;
    uint hs_long_count;    // long segments in the long list
    uint hs_long_binned;   // long segments in the tiles' lists
    uint hs_long_reserved; // their pairs, at most hs_long_capacity
    uint hs_long_wanted;   // the pairs every long segment asked for (modulo 2^32): the next build's capacity
    uint hs_offset_spare;
    uint hs_tile_offsets[];
};
// Segment indices: tile by tile in [0, hs_pairs), then, from hs_long_first, one word for each segment.
// A short segment (its box over at most HS_SHORT_TILES tiles) is listed in every tile of its box: at
// most HS_SHORT_TILES words a segment. A long one is listed in the tiles its line reaches
// (hs_long_tiles), while the hs_long_capacity words the build set aside for long pairs last; those past
// it go to the long list (from hs_long_first up), which every tile's work group reads through, and the
// listed ones are named from the other end (hs_long_first + segments - 1 down) for the scatter. The
// buffer is sized before the passes that fill it: the capacity comes from an earlier build's
// hs_long_wanted, or from a first prepare pass's when the resolution or segment count is new
// (compute_segments::run).
layout(std430, binding = 3) buffer hs_binned_buffer { uint hs_binned[]; };
const int HS_SHORT_TILES = 4;
uniform uint hs_long_first;

uniform int hs_resolution;
uniform int hs_tiles_x;
const int HS_TILE = 16; // texels per side of a tile: one work group of 256 invocations each

// The segment of a per-segment pass's invocation: groups of 256 in rows of up to 65535 groups.
uint hs_segment_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x * 256u + gl_GlobalInvocationID.x; }

// Tile `tile`'s texels, (x0, y0, x1, y1) half-open, clipped to the map.
ivec4 hs_tile_rect(uint tile) {
    ivec2 origin = HS_TILE * ivec2(int(tile % uint(hs_tiles_x)), int(tile / uint(hs_tiles_x)));
    return ivec4(origin, min(origin + HS_TILE, ivec2(hs_resolution)));
}
// Walks every segment of tile `tile` into hs_emit (the fragments inside `rect`, or the whole tile),
// the work group's invocations taking turns: the tile's own list, then the long list, as one range of
// turns. Loops here are do-while loops behind an if, and the two lists one loop: llvmpipe runs an
// if's body under a lane mask whether or not a lane takes it, and a while loop's body once more after
// its last turn, so each loop head costs a masked pass through the walk (BENCHMARKS.md, "llvmpipe's
// masked passes").
void hs_walk_current(ivec4 clip);
void hs_begin_segment(uint index);
bool hs_segment_box(ivec4 e, out ivec4 box);
void hs_walk_tile_rect(uint tile, ivec4 rect) {
    uint first = hs_tile_offsets[tile], listed = hs_tile_offsets[tile + 1u] - first, turns = listed + hs_long_count;
    uint j = gl_LocalInvocationIndex;
    if (j < turns) do {
        bool from_long_list = j >= listed;
        uint segment = hs_binned[from_long_list ? hs_long_first + (j - listed) : first + j];
        ivec4 box;
        // A long segment is walked where its box meets the rectangle.
        if (!from_long_list || (hs_segment_box(hs_segments[segment].ends, box) && box.z >= rect.x && box.x < rect.z && box.w >= rect.y &&
                                box.y < rect.w)) {
            hs_begin_segment(segment);
            hs_walk_current(rect);
        }
        j += uint(HS_TILE * HS_TILE);
    } while (j < turns);
}
void hs_walk_tile(uint tile) { hs_walk_tile_rect(tile, hs_tile_rect(tile)); }

// Float bits in an order that uint comparison keeps, for atomicMin and atomicMax on depths.
uint hs_ordered(float f) {
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float hs_from_ordered(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u); }

// Is p, moved by -(e, e^2), inside the open diamond of texel (c, r)? (detail::inside_diamond; a
// coordinate more than H from the centre leaves it at once, so the sum cannot overflow.)
bool hs_inside_diamond(ivec2 p, int c, int r) {
    int u = p.x - (c * HS_S + HS_H), v = p.y - (r * HS_S + HS_H);
    if (abs(u) > HS_H || abs(v) > HS_H) return false;
    int l1 = abs(u) + abs(v);
    return l1 < HS_H || (l1 == HS_H && u > 0);
}

// Texels [x0, x1) x [y0, y1) within the map's side that a segment's box, widened by one texel (the
// CPU's reach for thin lines), may touch; false when it misses the map (segment_bins::meets_map).
// GLSL's >> on an int extends the sign: a floor division by HS_S.
bool hs_segment_box(ivec4 e, out ivec4 box) {
    ivec2 lo = (min(e.xy, e.zw) - HS_S) >> HS_SUBPIXEL_BITS, hi = (max(e.xy, e.zw) + HS_S) >> HS_SUBPIXEL_BITS;
    if (hi.x < 0 || hi.y < 0 || lo.x >= hs_resolution || lo.y >= hs_resolution) return false;
    box = ivec4(max(lo, ivec2(0)), min(hi, ivec2(hs_resolution - 1)));
    return true;
}

// o v / A as q + r / A with 0 <= r < A, exactly, for 0 <= o <= 2^30 and |v| <= A <= 2^30 (so |q| <= o;
// within the guard band A <= 2^(21 + bits) <= 2^30, and 2A - 2, the most a partial remainder reaches
// here or in hs_walk's step, fits an int).
// When |o v| fits 32 bits (always for a segment under 2^16 sub-pixels, 256 texels at 8 bits) it is one unsigned
// division; otherwise o's bits are taken one at a time (long multiplication of v / A, in (q, r) form):
// each partial remainder stays below 2A, which fits an int.
ivec2 hs_product_quotient(int o, int v, int A) {
    uint hi, lo;
    umulExtended(uint(o), uint(abs(v)), hi, lo);
    if (hi == 0u) {
        uint q = lo / uint(A), r = lo - q * uint(A);
        if (v >= 0 || r == 0u) return ivec2(v >= 0 ? int(q) : -int(q), int(r));
        return ivec2(-int(q) - 1, A - int(r));
    }
    ivec2 unit = v == A ? ivec2(1, 0) : v >= 0 ? ivec2(0, v) : ivec2(-1, v + A); // v / A
    ivec2 qr = ivec2(0);
    for (int bit = findMSB(o); bit >= 0; --bit) {
        qr *= 2;
        if (qr.y >= A) qr += ivec2(1, -A);
        if (((o >> bit) & 1) != 0) {
            qr += unit;
            if (qr.y >= A) qr += ivec2(1, -A);
        }
    }
    return qr;
}

// The texel centres a segment crosses along its major axis, [first, last] (empty when first > last),
// from its ends' major coordinates in sub-pixels: ceil((end - H) / S), by the shift's floor.
ivec2 hs_centres_crossed(int major_a, int major_b) {
    int lo_end = min(major_a, major_b), hi_end = max(major_a, major_b);
    return ivec2((lo_end - HS_H + HS_S - 1) >> HS_SUBPIXEL_BITS, ((hi_end - HS_H + HS_S - 1) >> HS_SUBPIXEL_BITS) - 1);
}
// The minor coordinate at centre m (first <= m <= last), minor_a + o d_minor / A sub-pixels with o its
// distance from a along the major axis, in [0, A]: as (k, r), k + r / A, 0 <= r < A.
ivec2 hs_minor_at(int m, int major_a, int minor_a, int sign, int d_minor, int A) {
    ivec2 qr = hs_product_quotient(sign * (m * HS_S + HS_H - major_a), d_minor, A);
    return ivec2(minor_a + qr.x, qr.y);
}

// The tiles a long segment's fragments can reach, fewer than its box's (a diagonal segment's box holds
// the square of the tiles its line crosses). Along the major axis, tile t holds the walk's centres m
// in [16t, 16t + 15]; their fragments' minor texels are floor(minor(m) / S), or one less on a tie,
// monotone in m (hs_walk), and the fragment at a's own texel lies one centre before the first or after
// the last, within two texels of that centre's minor texel. So each major tile's centres (the
// segment's taken from first - 1 to last + 1) and two texels either side of their minor texels hold
// every fragment: a tile too many costs a walk that emits nothing, a tile missed would lose fragments
// (the compute tests compare every texel).
// Counts the tiles; mode 1 also counts the segment in each tile's count, mode 2 lists it there (the
// scatter, in the same order, so the counts match).
uint hs_long_tiles(ivec4 e, ivec4 box, int mode, uint segment) {
    int dx = e.z - e.x, dy = e.w - e.y;
    bool x_major = abs(dx) >= abs(dy);
    int major_a = x_major ? e.x : e.y, major_b = x_major ? e.z : e.w, minor_a = x_major ? e.y : e.x;
    int d_minor = x_major ? dy : dx, A = abs(major_b - major_a), sign = major_b > major_a ? 1 : -1;
    ivec2 crossed = hs_centres_crossed(major_a, major_b);
    int first = crossed.x, last = crossed.y;
    ivec2 majors = x_major ? box.xz : box.yw, minors = x_major ? box.yw : box.xz;
    uint tiles = 0u;
    for (int t = majors.x / HS_TILE; t <= majors.y / HS_TILE; ++t) {
        int m0 = max(max(t * HS_TILE, majors.x), first - 1), m1 = min(min(t * HS_TILE + HS_TILE - 1, majors.y), last + 1);
        if (m0 > m1) continue;
        ivec2 reach = minors; // no centre crossed (never for a long segment): the whole box
        if (first <= last) {
            int n0 = hs_minor_at(clamp(m0, first, last), major_a, minor_a, sign, d_minor, A).x >> HS_SUBPIXEL_BITS;
            int n1 = hs_minor_at(clamp(m1, first, last), major_a, minor_a, sign, d_minor, A).x >> HS_SUBPIXEL_BITS;
            reach = ivec2(max(min(n0, n1) - 2, minors.x), min(max(n0, n1) + 2, minors.y));
        }
        if (reach.x > reach.y) continue;
        for (int u = reach.x / HS_TILE; u <= reach.y / HS_TILE; ++u) {
            uint tile = uint(x_major ? u * hs_tiles_x + t : t * hs_tiles_x + u);
            if (mode == 1) atomicAdd(hs_tile_counts[tile], 1u);
            else if (mode == 2) hs_binned[hs_tile_offsets[tile] + atomicAdd(hs_tile_counts[tile], 1u)] = segment;
            ++tiles;
        }
    }
    return tiles;
}

void hs_emit(int x, int y); // defined by each pass

// Every fragment of a -> b inside the texel rectangle clip = (x0, y0, x1, y1), half-open, by the
// diamond-exit rule: the fragments of rasterize_line (set_up_line, the walk, then start_fragment), in
// 32-bit words. The minor coordinate at a centre is k + r / A sub-pixels, A = |d_major|, whose parts
// stay within the guard band and below A, as the CPU's set_up_line keeps it (the CPU takes the
// set-up's quotients by one 64-bit division each, this by hs_product_quotient): the same fragments.
void hs_walk(ivec2 a, ivec2 b, ivec4 clip) {
    if (a == b) return;
    int dx = b.x - a.x, dy = b.y - a.y;
    bool x_major = abs(dx) >= abs(dy);
    int major_a = x_major ? a.x : a.y, major_b = x_major ? b.x : b.y;
    int d_major = x_major ? dx : dy, d_minor = x_major ? dy : dx;
    int minor_a = x_major ? a.y : a.x;
    ivec2 crossed = hs_centres_crossed(major_a, major_b);
    int first = crossed.x, last = crossed.y;
    int m_begin = max(first, x_major ? clip.x : clip.y), m_end = min(last, (x_major ? clip.z : clip.w) - 1);
    bool lower_on_tie = !x_major || dy == 0 || ((dx > 0) != (dy > 0));
    int steps = max(m_end - m_begin + 1, 0);
    int A = abs(d_major), sign = d_major > 0 ? 1 : -1;
    ivec2 start = ivec2(0), step = ivec2(0);
    if (steps > 0) {
        start = hs_minor_at(m_begin, major_a, minor_a, sign, d_minor, A); // first <= m_begin <= last
        step = hs_product_quotient(HS_S, sign * d_minor, A);             // per centre
    }
    // a's own texel, where no centre crossed gives it: one turn after the steps, so that the emission
    // code is met once a turn (llvmpipe runs a call in every turn whether or not a lane takes it).
    int ax = (a.x - 1) >> HS_SUBPIXEL_BITS, ay = (a.y - 1) >> HS_SUBPIXEL_BITS;
    int a_major = x_major ? ax : ay;
    bool a_emits = hs_inside_diamond(a, ax, ay) && (a_major < first || a_major > last) && !hs_inside_diamond(b, ax, ay) && ax >= clip.x &&
                   ax < clip.z && ay >= clip.y && ay < clip.w;
    int turns = steps + (a_emits ? 1 : 0);
    int k = start.x, r = start.y;
    int i = 0;
    if (turns > 0) do {
        int x = ax, y = ay;
        bool emits = true;
        if (i < steps) {
            int n = k >> HS_SUBPIXEL_BITS, m = m_begin + i;
            int minor = (lower_on_tie && r == 0 && (k & (HS_S - 1)) == 0) ? n - 1 : n;
            x = x_major ? m : minor;
            y = x_major ? minor : m;
            emits = x >= clip.x && x < clip.z && y >= clip.y && y < clip.w && !hs_inside_diamond(b, x, y);
            k += step.x;
            r += step.y;
            if (r >= A) {
                r -= A;
                ++k;
            }
        }
        if (emits) hs_emit(x, y);
    } while (++i < turns);
}

// The segment being walked, and its fragments' depth and optical depth (detail::segment_shader).
hs_segment hs_current = hs_segment(ivec4(0), vec4(0.0), vec4(0.0));
vec2 hs_delta = vec2(0.0);    // b - a in sub-pixels, converted exactly or correctly rounded
float hs_inv_length2 = 0.0;   // 1 / |b - a|^2, correctly rounded (hs_div_rn)

bool hs_constant_alpha = false;
float hs_constant_b = 0.0;
void hs_walk_current(ivec4 clip) {
    hs_walk(hs_current.ends.xy, hs_current.ends.zw, clip);
}

// Window parameter of texel centre (x, y) along the segment, clamped to [0, 1]: segment_shader::parameter,
// operation for operation (precise: each product rounded on its own; the offsets are exact 32-bit
// integers within the guard band, and GLSL converts them to float correctly rounded). -0 gives +0.
float hs_parameter(int x, int y) {
    precise float px = float(x * HS_S + HS_H - hs_current.ends.x), py = float(y * HS_S + HS_H - hs_current.ends.y);
    precise float along_x = px * hs_delta.x, along_y = py * hs_delta.y;
    precise float dot = along_x + along_y;
    precise float t = dot * hs_inv_length2;
    return t > 0.0 ? min(t, 1.0) : 0.0;
}
// a + (b - a) s, rounded as the CPU rounds it.
float hs_lerp_exact(float a, float b, float s) {
    precise float d = (b - a) * s;
    precise float r = a + d;
    return r;
}

float hs_attribute_parameter(float t) {
    if (hs_current.depth_w.z == hs_current.depth_w.w) return t;
    precise float wa = (1.0 - t) * hs_current.depth_w.z;
    precise float wb = t * hs_current.depth_w.w;
    precise float sum = wa + wb;
    return hs_div_rn(wb, sum);
}
float hs_fragment_depth_at(float s) { return hs_lerp_exact(hs_current.depth_w.x, hs_current.depth_w.y, s); }

uniform bool hs_use_fixed_alpha;
uniform float hs_fixed_alpha;
uniform float hs_footprint;       // light_space::texel_size(0.5)
uniform bool hs_footprint_varies; // a perspective light with depth weighting
uniform vec4 hs_footprint_terms;  // 2 half_extent, near, far - near, resolution: texel_size(depth)

float hs_fragment_alpha_at(float s, float depth) {
    float alpha;
    if (hs_use_fixed_alpha) {
        alpha = hs_fixed_alpha;
    } else {
        float thickness = hs_lerp_exact(hs_current.attributes.x, hs_current.attributes.y, s);
        float opacity = hs_lerp_exact(hs_current.attributes.z, hs_current.attributes.w, s);
        float footprint = hs_footprint;
        if (hs_footprint_varies) {
            precise float distance = hs_footprint_terms.y + depth * hs_footprint_terms.z;
            precise float width = hs_footprint_terms.x * distance;
            footprint = hs_div_rn(width, hs_footprint_terms.w);
        }
        precise float a = opacity * min(1.0, hs_div_rn(thickness, footprint));
        alpha = a;
    }
    return alpha > 0.0 ? min(alpha, HS_ALPHA_MAX) : 0.0;
}

// b = -ln(1 - alpha) for alpha in [0, 1), operation for operation as hairshadow::optical_depth_of
// computes it (precise: no fused multiply-adds; quotients correctly rounded), so the same bits.
float hs_optical_depth_of(float alpha) {
    if (alpha < 0.5) {
        float s = hs_div_rn(alpha, 2.0 - alpha);
        precise float s2 = s * s;
        precise float p = 1.0 / 15.0;
        const float c[7] = float[7](1.0 / 13.0, 1.0 / 11.0, 1.0 / 9.0, 1.0 / 7.0, 1.0 / 5.0, 1.0 / 3.0, 1.0);
        for (int i = 0; i < 7; ++i) p = c[i] + s2 * p;
        precise float b = (2.0 * s) * p;
        return b;
    }
    float u = 1.0 - alpha;
    uint bits = floatBitsToUint(u);
    int e = int((bits >> 23) & 0xffu) - 127;
    float m = uintBitsToFloat((bits & 0x7fffffu) | 0x3f800000u);
    if (m > 1.41421356) {
        m *= 0.5;
        ++e;
    }
    float s = hs_div_rn(m - 1.0, m + 1.0);
    precise float s2 = s * s;
    precise float p = 1.0 / 11.0;
    const float c[5] = float[5](1.0 / 9.0, 1.0 / 7.0, 1.0 / 5.0, 1.0 / 3.0, 1.0);
    for (int i = 0; i < 5; ++i) p = c[i] + s2 * p;
    precise float ln_u = float(e) * 0.693147182 + (2.0 * s) * p;
    return -ln_u;
}

// Starts segment `index`: a segment of one alpha (a fixed alpha, or constant thickness and opacity
// with a footprint that does not change with depth) works out its b once, as the CPU does.
void hs_begin_segment(uint index) {
    hs_current = hs_segments[index];
    hs_delta = vec2(hs_current.ends.zw - hs_current.ends.xy);
    precise float dx2 = hs_delta.x * hs_delta.x, dy2 = hs_delta.y * hs_delta.y;
    precise float length2 = dx2 + dy2;
    hs_inv_length2 = hs_div_rn(1.0, length2);
#ifdef HS_ONE_ALPHA
    hs_constant_alpha = true; // every segment of the run has one alpha (compute_segments::one_alpha)
#else
    hs_constant_alpha = hs_use_fixed_alpha || (!hs_footprint_varies && hs_current.attributes.x == hs_current.attributes.y &&
                                                hs_current.attributes.z == hs_current.attributes.w);
#endif
#ifndef HS_DEPTH_ONLY
    if (hs_constant_alpha) hs_constant_b = hs_optical_depth_of(hs_fragment_alpha_at(0.0, hs_current.depth_w.x));
#endif
}

// The linear depth of the current segment's fragment at texel (x, y).
float hs_fragment_depth_of(int x, int y) { return hs_fragment_depth_at(hs_attribute_parameter(hs_parameter(x, y))); }
// Its depth and optical depth.
void hs_shade(int x, int y, out float depth, out float b) {
    float s = hs_attribute_parameter(hs_parameter(x, y));
    depth = hs_fragment_depth_at(s);
#ifdef HS_ONE_ALPHA
    b = hs_constant_b;
#else
    b = hs_constant_alpha ? hs_constant_b : hs_optical_depth_of(hs_fragment_alpha_at(s, depth));
#endif
}
