// A consumer of hairshadow: builds the exact reference of a small procedural model and checks that
// light passes in front of the hair and is dimmed behind it.
#include <hairshadow/hairshadow.hpp>

#include <cstdio>

int main() {
    using namespace hairshadow;
    const auto model = make_procedural({.style = hair_style::wavy, .strands = 500, .segments = 16});
    const auto light = light_space::fit(light_spec::directional({0, -1, 0}), model.bounds(), 64);
    const deep_shadow_map dsm(rasterize(model, light), light);
    int shadowed = 0;
    bool lit_in_front = true;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            shadowed += dsm.transmittance(x, y, 1.0f) < 1.0f;
            lit_in_front = lit_in_front && dsm.transmittance(x, y, 0.0f) == 1.0f;
        }
    std::printf("%d of 64x64 texels are shadowed behind the hair\n", shadowed);
    return lit_in_front && shadowed > 100 ? 0 : 1;
}
