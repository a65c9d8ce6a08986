// A consumer of hairshadow's GL back end (hairshadow::gl_osmesa, found with find_package): an OSMesa
// context loaded by the package's glad, deep opacity maps of a small procedural model built on GL and
// on the CPU, and the two compared at the hair's points: the maps read back (within 1e-5) and the GLSL
// look-up (within 1e-4), a tenth of them shadowed. Returns nonzero unless so.
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/osmesa_context.hpp>
#include <hairshadow/hairshadow.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

int main() try {
    using namespace hairshadow;
    gl::osmesa_context context(4, 5);
    if (!gladLoadGL(context.loader())) throw gl::gl_error("cannot load GL");
    std::printf("%s\n", context.description().c_str());

    const hair_model model = make_procedural({.style = hair_style::wavy, .strands = 500, .segments = 16});
    const light_space light = light_space::fit(light_spec::directional({0, -1, 0}), model.bounds(), 128);
    deep_opacity_maps<3> on_cpu;
    on_cpu.build(model, light);
    const gl::hair_mesh strands(model);
    gl::maps<deep_opacity_maps<3>> on_gl;
    on_gl.set_build_path(gl::build_path::compute); // the CPU's line rule: the CPU's fragments
    on_gl.build(strands, light);

    const std::vector<glm::vec3>& points = model.points;
    std::vector<float> cpu(points.size()), back(points.size());
    on_cpu.transmittance(points, cpu);
    on_gl.to_cpu().transmittance(points, back);
    const std::vector<float> glsl = gl::point_queries(on_gl.lookup_source()).run(points, [&](GLuint p) { on_gl.bind_lookup(p); });
    float worst_back = 0, worst_glsl = 0;
    std::size_t shadowed = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        worst_back = std::max(worst_back, std::abs(back[i] - cpu[i]));
        worst_glsl = std::max(worst_glsl, std::abs(glsl[i] - cpu[i]));
        shadowed += cpu[i] < 0.9f;
    }
    std::printf("%zu points, %zu shadowed; GL against the CPU: read back %.2g, GLSL look-up %.2g\n", points.size(), shadowed,
                double(worst_back), double(worst_glsl));
    return worst_back <= 1e-5f && worst_glsl <= 1e-4f && shadowed > points.size() / 10 ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
