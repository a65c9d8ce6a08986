// 01-exact-reference: the exact transmittance of a deep shadow map (Lokovic & Veach 2000) for a
// procedural curly model lit from above, queried at a few points along one light ray, and the same
// after Lokovic-Veach compression. Prints a small table; writes nothing.
#include <hairshadow/hairshadow.hpp>

#include <cstdio>

int main() {
    using namespace hairshadow;
    const hair_model model = make_procedural({.style = hair_style::curly, .strands = 3000, .segments = 24, .seed = 1});
    const light_space light = light_space::fit(light_spec::directional({0, -1, 0}), model.bounds(), 256);
    // Both are streamed tile by tile from the model; the compressed one never holds the exact one.
    const deep_shadow_map exact(model, light);
    const compressed_deep_shadow_map compressed(model, light, 0.01f);
    std::printf("%zu segments -> %zu fragments; compressed to %zu vertices (%.1f%%)\n", model.segment_count(), exact.fragment_count(),
                compressed.vertex_count(), 100.0 * double(compressed.vertex_count()) / double(2 * exact.fragment_count()));
    std::printf("depth   exact T   compressed T\n");
    for (float depth = 0.0f; depth <= 1.0f; depth += 0.1f)
        std::printf("%.2f    %.4f    %.4f\n", double(depth), double(exact.transmittance(128, 128, depth)),
                    double(compressed.transmittance(128, 128, depth)));
}
