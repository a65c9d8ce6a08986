// The mesh's depth shadow map: linear depth from the light (hs_view, hs_near, hs_far of
// raster/vertex's uniforms), the nearest kept by the depth test.
layout(location = 0) out float hs_depth_out;
in float hs_v_depth;
void main() { hs_depth_out = hs_v_depth; }
