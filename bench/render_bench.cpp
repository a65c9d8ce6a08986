// Shaded renders of the Sintel hair on its head at 512x512 on the CPU: the opaque renderer and each
// transparency mode (shadows from occupancy maps 128/4 built once), and on GL under OSMesa the
// renderer's passes, with the depth-peeling layers of exact blending. Run: build/bench/hairshadow_render_bench
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/osmesa_context.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/obj_format.hpp>

#include <benchmark/benchmark.h>

#include <memory>

namespace {

using namespace hairshadow;

struct prepared {
    scene sc;
    camera cam;
    occupancy_maps<128, 4> shadows;
    std::vector<lit_light> lights;
};

prepared& sintel() {
    static prepared p = [] {
        prepared out;
        const std::string dir = std::string(HAIRSHADOW_SHARED_DIR) + "/data/sintel/";
        out.sc.hair = read_tfx(dir + "sintel_hair.16points.tfx");
        out.sc.mesh = read_obj(dir + "sintel_head.obj").mesh;
        out.sc.lights = {{light_spec::directional({-0.7f, -0.9f, -0.45f}), glm::vec3(1.1f)}};
        const auto space = light_space::fit(out.sc.lights[0].spec, out.sc.bounds(), 512);
        out.shadows.build(rasterize(out.sc.hair, space), space);
        out.cam = camera::framing(out.sc.bounds(), 25.0f, 10.0f, 512, 512, 1.15f);
        return out;
    }();
    if (p.lights.empty()) {
        const auto space = light_space::fit(p.sc.lights[0].spec, p.sc.bounds(), 512);
        p.lights.push_back({p.sc.lights[0], query_of(p.shadows), depth_shadow_map(p.sc.mesh, space)});
    }
    return p;
}

void cpu_render(benchmark::State& state, transparency mode) {
    auto& p = sintel();
    for (auto _ : state) benchmark::DoNotOptimize(render_transparent(p.sc, p.cam, p.lights, mode, 0.4f));
}
BENCHMARK_CAPTURE(cpu_render, opaque, transparency::none)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(cpu_render, occupancy, transparency::occupancy)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(cpu_render, weighted, transparency::weighted)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(cpu_render, exact, transparency::exact)->Unit(benchmark::kMillisecond)->UseRealTime();

void gl_render(benchmark::State& state, transparency mode) {
    auto& p = sintel();
    static gl::osmesa_context context(4, 5);
    if (!gladLoadGL(context.loader())) throw gl::gl_error("cannot load GL");
    const auto space = light_space::fit(p.sc.lights[0].spec, p.sc.bounds(), 512);
    const gl::hair_mesh mesh(p.sc.hair);
    gl::maps<occupancy_maps<128, 4>> maps;
    maps.build(mesh, space);
    gl::scene_renderer renderer(p.sc);
    renderer.add_light(p.sc.lights[0], maps);
    renderer.set_transparency(mode, 0.4f);
    renderer.render(p.cam); // compiles the mode's programs
    for (auto _ : state) benchmark::DoNotOptimize(renderer.render(p.cam));
    if (mode == transparency::exact) state.counters["peeled_layers"] = renderer.peeled_layers(); // a draw of the hair each, and two more
}
BENCHMARK_CAPTURE(gl_render, opaque, transparency::none)->Name("gl_osmesa_render/opaque")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(gl_render, occupancy, transparency::occupancy)->Name("gl_osmesa_render/occupancy")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(gl_render, weighted, transparency::weighted)->Name("gl_osmesa_render/weighted")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(gl_render, exact, transparency::exact)->Name("gl_osmesa_render/exact")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

} // namespace

BENCHMARK_MAIN();
