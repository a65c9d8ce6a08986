// The compute build path on whatever GPU EGL finds (or llvmpipe through OSMesa), in one run: for each
// model, resolution and method, the compute-built maps checked against the CPU maps of the same model
// and light (every texel: occupancy and states bit for bit, sums within 1e-6 relative), then both GL build paths timed by GL timer queries
// and the wall clock (medians of --repeat), beside the CPU's tiled build. Prints a Markdown table;
// exits 1 if any compute-built map differs from the CPU's. The one program a GPU run needs:
//   build/bench/hairshadow_gl_gpu_check [--context egl|osmesa] [--large] [--repeat N] [--model SOURCE]...
// --large adds 2048x2048 (and, without --model, the 1.5M-segment curly model); --model replaces the
// Sintel model (a file or a procedural spec; repeatable). scripts/gpu_check.sh runs it on a GPU machine.
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/egl_context.hpp>
#include <hairshadow/gl/context/osmesa_context.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/methods/spec.hpp>

#include "../tests/gl/compute_comparison.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace hairshadow;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// Milliseconds of `work`: on the GPU, by a GL_TIME_ELAPSED query, and on the wall clock until
/// glFinish returns (some drivers' timer queries leave compute dispatches out: llvmpipe under EGL reads 0).
struct timing {
    double gpu, wall;
};
template <class Work>
timing time_of(GLuint query, Work&& work) {
    const auto start = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query);
    work();
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    return {double(ns) * 1e-6, wall};
}

struct outcome {
    bool exact = true;
};

template <class Method>
void check_and_time(const Method& method, const method_spec& spec, const hair_model& model, const gl::hair_mesh& mesh, const light_space& light,
                    int repeat, GLuint query, outcome& all) {
    // The check: compute-built maps against the CPU's.
    Method cpu = method;
    std::vector<double> cpu_times;
    for (int i = 0; i <= repeat; ++i) {
        const auto start = std::chrono::steady_clock::now();
        cpu.build(model, light);
        if (i > 0) cpu_times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light);
    auto checked = gl::detail::maps_of_method(method);
    checked.build(pass);
    const auto c = test::compare_maps(cpu, checked, gl::detail::read_range(*pass.textures()), test::cpu_occupancy(model, light), light.resolution());
    all.exact = all.exact && c.exact();
    // The times: each path's full build (its own light pass included), the first build apart.
    timing times[2] = {{0, 0}, {0, 0}};
    for (const auto path : {gl::build_path::compute, gl::build_path::raster}) {
        auto maps = gl::detail::maps_of_method(method);
        maps.set_build_path(path);
        maps.build(mesh, light);
        glFinish();
        std::vector<double> gpu, wall;
        for (int i = 0; i < repeat; ++i) {
            const auto t = time_of(query, [&] { maps.build(mesh, light); });
            gpu.push_back(t.gpu), wall.push_back(t.wall);
        }
        times[path == gl::build_path::compute ? 0 : 1] = {median(gpu), median(wall)};
    }
    std::printf("| %s | %.2f / %.2f | %.2f / %.2f | %.2fx | %.1f | %s (%ld texels, worst sum %.1e) |\n", spec.text.c_str(), times[0].gpu,
                times[0].wall, times[1].gpu, times[1].wall, times[0].wall > 0 ? times[1].wall / times[0].wall : 0.0, median(cpu_times),
                c.exact() ? "exact" : "DIFFERS", c.occupied, c.worst);
    std::fflush(stdout);
}

} // namespace

int main(int argc, char** argv) {
    std::string context = "egl";
    bool large = false;
    int repeat = 5;
    std::vector<std::string> models;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--context" && i + 1 < argc) context = argv[++i];
        else if (a == "--model" && i + 1 < argc) models.push_back(argv[++i]);
        else if (a == "--large") large = true;
        else if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
        else {
            std::fprintf(stderr, "usage: hairshadow_gl_gpu_check [--context egl|osmesa] [--large] [--repeat N] [--model SOURCE]...\n");
            return 2;
        }
    }
    try {
        std::unique_ptr<gl::headless_context> ctx;
        if (context == "osmesa") ctx = std::make_unique<gl::osmesa_context>(4, 5);
        else ctx = std::make_unique<gl::egl_context>(4, 5);
        if (!gladLoadGL(ctx->loader())) throw gl::gl_error("cannot load GL");
        gl::require_compute_path("the GPU check");
        GLuint query = 0;
        glGenQueries(1, &query);
        std::printf("%s. Times: medians of %d full builds (light pass included), by GL timer queries and on the wall clock to glFinish; "
                "CPU: the tiled build, wall time, "
                    "%u threads.\n\n",
                    ctx->description().c_str(), repeat, execution{}.resolved());
        const bool defaulted = models.empty();
        if (defaulted) models.push_back(std::string(HAIRSHADOW_SHARED_DIR) + "/data/sintel/sintel_hair.16points.tfx");
        std::vector<int> resolutions = {512};
        if (large) {
            if (defaulted) models.push_back("procedural:curly:strands=10000:segments=150");
            resolutions.push_back(2048);
        }
        outcome all;
        for (const auto& name : models) {
            const auto model = load_model(name);
            const gl::hair_mesh mesh(model);
            for (const int res : resolutions) {
                const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), res);
                std::printf("**%s**, %zu segments, %dx%d\n\n| method | compute, timer / wall (ms) | raster, timer / wall (ms) | raster / compute (wall) | CPU tiled (ms) | compute maps against the CPU's |\n"
                            "|---|---|---|---|---|---|\n",
                            name.substr(name.find_last_of('/') + 1).c_str(), model.segment_count(), res, res);
                for_each_example([&](const auto& example) { // the methods bench times by default, every family's
                    using Method = typename std::decay_t<decltype(example)>::method_type;
                    if constexpr (!std::is_same_v<Method, exact_reference>)
                        if (example.lists & in_bench) check_and_time(Method(), parse_method_spec(example.spec), model, mesh, light, repeat, query, all);
                });
                std::printf("\n");
            }
        }
        glDeleteQueries(1, &query);
        if (!all.exact) std::fprintf(stderr, "error: compute-built maps differ from the CPU's\n");
        return all.exact ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
