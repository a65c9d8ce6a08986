// Occupancy-map reconstruction (Sintorn & Assarsson 2009, sections 3.1-3.3): each set bit in slab i is
// worth the slab's sum over its set bits; a query interpolates inside its slice, so slab boundaries
// are exact. HS_LAYERS slices in HS_LAYERS / 32 words, HS_SLABS slabs. Mirrors occupancy_bitcount.
const int HS_WORDS = HS_LAYERS / 32;
const int HS_PER_SLAB = HS_LAYERS / HS_SLABS;

int hs_count_bits(uint bits[HS_WORDS], int begin, int end) {
    int n = 0;
    for (int w = begin / 32; w * 32 < end; ++w) {
        uint word = bits[w];
        int lo = max(begin - w * 32, 0), hi = min(end - w * 32, 32);
        if (hi < 32) word &= (1u << uint(hi)) - 1u;
        word &= ~((1u << uint(lo)) - 1u);
        n += bitCount(word);
    }
    return n;
}

float hs_occupancy_optical_depth(hs_layer_position p, uint bits[HS_WORDS], float slabs[HS_SLABS]) {
    if (p.index < 0) return 0.0;
    int slab = min(p.index, HS_LAYERS) / HS_PER_SLAB;
    float omega = 0.0;
    for (int i = 0; i < min(slab, HS_SLABS); ++i) omega += hs_decode(slabs[i]);
    if (p.index >= HS_LAYERS) return omega;
    int first = slab * HS_PER_SLAB;
    int set = hs_count_bits(bits, first, first + HS_PER_SLAB);
    if (set == 0) return omega;
    float per_bit = hs_decode(slabs[slab]) / float(set);
    bool occupied = ((bits[p.index / 32] >> uint(p.index % 32)) & 1u) != 0u;
    return omega + per_bit * (float(hs_count_bits(bits, first, p.index)) + (occupied ? p.fraction : 0.0));
}

// The optical depth in front of a fragment assigned to slice k: the slabs in front, and the set bits
// of its own slab before slice k, each worth the slab's mean (Sintorn & Assarsson 2009, section 3.4:
// divided by one fragment's -ln(1 - alpha) it is the depth order o). Mirrors
// occupancy_bitcount::optical_depth_in_front.
float hs_occupancy_optical_depth_in_front(int k, uint bits[HS_WORDS], float slabs[HS_SLABS]) {
    int slab = k < 0 ? HS_SLABS : k / HS_PER_SLAB; // a fragment the placement dropped: behind everything
    float omega = 0.0;
    for (int i = 0; i < min(slab, HS_SLABS); ++i) omega += hs_decode(slabs[i]);
    if (k < 0) return omega;
    int first = slab * HS_PER_SLAB;
    int set = hs_count_bits(bits, first, first + HS_PER_SLAB);
    if (set == 0) return omega;
    return omega + hs_decode(slabs[slab]) / float(set) * float(hs_count_bits(bits, first, k));
}
