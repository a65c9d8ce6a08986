// What Fourier opacity maps and moment shadow maps share (mirrors
// reconstruction/detail/depth_projection.hpp): a fragment's place in its texel's depth range, 0 at the
// nearest fragment and 1 at the furthest, divided as the CPU divides (a quotient of floats in double,
// rounded once, is the correctly rounded float quotient).
float hs_position_in_range(float nearest, float furthest, float depth) {
    precise float span = furthest - nearest;
    precise float offset = depth - nearest;
    return span > 0.0 ? clamp(float(double(offset) / double(span)), 0.0, 1.0) : 0.0;
}
