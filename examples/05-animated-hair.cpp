// 05-animated-hair: hair that moves, its shadow maps rebuilt every frame, as a renderer does.
// Curly hair sways in the wind (procedural/motion.hpp) while the light orbits it. On the CPU, deep
// opacity maps and occupancy maps are rebuilt straight from the moved model into the same objects
// (once warm, a rebuild allocates nothing). On GL (a headless EGL context, where this example was
// built with it), the points live in a vertex buffer that the "engine" owns, with its own stride,
// and the maps read them from there: only the positions change hands each frame.
//
//   05-animated-hair [FRAMES]
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/procedural/motion.hpp>

#ifdef HAIRSHADOW_EXAMPLE_GL
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/egl_context.hpp>
#endif

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace hairshadow;

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/// A frame's light: the sun turning once around the model every four seconds.
light_space light_at(float t, const aabb& box, int resolution) {
    return light_space::fit(orbit_light(light_spec::directional({0.6f, -1.0f, 0.6f}), t, 4.0f, box.center()), box, resolution);
}

} // namespace

int main(int argc, char** argv) try {
    const int frames = argc > 1 ? std::max(2, std::atoi(argv[1])) : 24;
    const sway_motion sway(make_procedural({.style = hair_style::curly, .strands = 4000, .segments = 32}), {.amplitude_degrees = 20.0f});
    // One box for every frame (the rest pose, grown by how far a tip can swing): the maps' frustum
    // stays still while the hair moves in it.
    const aabb box = sway.rest().bounds().expanded(0.3f * sway.rest().bounds().diagonal());
    std::printf("%zu strands, %zu segments, %d frames at 30 fps\n", sway.rest().strand_count(), sway.rest().segment_count(), frames);

    // CPU: the same two objects rebuilt from the moved model every frame.
    hair_model hair;
    deep_opacity_maps<3> dom;
    occupancy_maps<128, 4> occ;
    std::vector<double> dom_ms, occ_ms;
    float shadowed_tip = 0.0f;
    for (int f = 0; f < frames; ++f) {
        const float t = float(f) / 30.0f;
        sway.pose(t, hair);
        const light_space light = light_at(t, box, 512);
        auto start = std::chrono::steady_clock::now();
        dom.build(hair, light);
        dom_ms.push_back(ms_since(start));
        start = std::chrono::steady_clock::now();
        occ.build(hair, light);
        occ_ms.push_back(ms_since(start));
        shadowed_tip = occ.transmittance(hair.points[hair.strand_offsets[1] - 1]);
    }
    std::printf("CPU rebuild per frame, median: DOM 3 %.1f ms, OCC 128/4 %.1f ms (the first: %.1f and %.1f ms)\n", median(dom_ms), median(occ_ms),
                dom_ms.front(), occ_ms.front());
    std::printf("transmittance at the first strand's tip in the last frame: %.3f\n", shadowed_tip);

#ifdef HAIRSHADOW_EXAMPLE_GL
    gl::egl_context context(4, 3);
    if (!gladLoadGL(context.loader())) throw gl::gl_error("cannot load GL");
    std::printf("%s\n", context.description().c_str());
    // The engine's vertex buffer: position, then a normal the shadow maps never read.
    struct engine_vertex {
        glm::vec3 position, normal;
    };
    std::vector<engine_vertex> vertices(sway.rest().point_count(), engine_vertex{{}, {0, 0, 1}});
    gl::buffer engine_buffer = gl::make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, engine_buffer.get());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(engine_vertex)), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    gl::point_buffers points;
    points.point_count = vertices.size();
    points.positions = {engine_buffer.get(), 0, GLsizei(sizeof(engine_vertex))};
    points.uniform_thickness = sway.rest().thickness_at(0); // no thickness or opacity buffers: one value each
    const gl::hair_mesh mesh(points, gl::strand_segments{sway.rest().strand_count(), sway.rest().strand_size(0)});
    gl::maps<deep_opacity_maps<3>> gl_dom;
    std::vector<double> gl_ms;
    for (int f = 0; f < frames; ++f) {
        const float t = float(f) / 30.0f;
        sway.pose(t, hair); // stands in for a simulation that writes the engine's buffer
        for (std::size_t i = 0; i < vertices.size(); ++i) vertices[i].position = hair.points[i];
        glBindBuffer(GL_ARRAY_BUFFER, engine_buffer.get());
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(vertices.size() * sizeof(engine_vertex)), vertices.data());
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        const auto start = std::chrono::steady_clock::now();
        gl_dom.build(mesh, light_at(t, box, 512));
        glFinish(); // the time of the GPU's work, not of queueing it
        gl_ms.push_back(ms_since(start));
    }
    // The GL maps answer as the CPU maps of the same frame.
    const deep_opacity_maps<3> from_gl = gl_dom.to_cpu();
    const glm::vec3 tip = hair.points[hair.strand_offsets[1] - 1];
    std::printf("GL rebuild per frame, median: DOM 3 %.1f ms; at the first strand's tip GL gives %.3f, the CPU %.3f\n", median(gl_ms),
                from_gl.transmittance(tip), dom.transmittance(tip));
#endif
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
