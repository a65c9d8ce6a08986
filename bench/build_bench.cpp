// Full rebuilds of a method's maps from the model (rasterise and build), the old path against the new
// in one run: a reused rasterizer's fragment buffer, then the method's build from it ("buffer"),
// against the tiled build straight from the model with its run-time line walk ("tiled", AVX-512 where
// the CPU has it) and with the portable scalar walk ("tiled_scalar"); and the tiled build's cold
// first call ("tiled_cold": a new map object each time, allocation and first touch included).
// Curly 1.5M (procedural:curly:strands=10000:segments=150) and Sintel, 512x512 and 2048x2048.
// Run: build/bench/hairshadow_build_bench --benchmark_filter=... --benchmark_repetitions=5
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <benchmark/benchmark.h>

#include "bench_models.hpp"

#include <map>
#include <string>

namespace {

using namespace hairshadow;

using bench::model;

enum class path { buffer, tiled, tiled_scalar, tiled_cold };

void rebuild(benchmark::State& state, const std::string& spec, const std::string& name, int res, unsigned threads, path how) {
    const auto& m = model(name);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), res);
    raster_options o;
    o.exec.threads = threads;
    if (how == path::tiled_scalar) o.instructions = instruction_set::scalar;
    rasterizer raster(o);
    auto map = make_shadow_map(spec);
    auto build = [&] {
        if (how == path::buffer) map->build(raster(m, light), light, o.exec);
        else map->build(m, light, o);
    };
    build(); // the first build allocates: rebuilds are timed
    for (auto _ : state) {
        if (how == path::tiled_cold) {
            state.PauseTiming();
            map = make_shadow_map(spec);
            state.ResumeTiming();
        }
        build();
    }
    state.counters["fragments/s"] = benchmark::Counter(double(map->fragment_count()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

const int registered = [] {
    const std::pair<path, const char*> paths[] = {{path::buffer, "buffer"}, {path::tiled, "tiled"}, {path::tiled_scalar, "tiled_scalar"},
                                                  {path::tiled_cold, "tiled_cold"}};
    for (const std::string name : {"curly1.5M", "sintel"})
        for (int res : {512, 2048})
            for (unsigned threads : {0u, 1u})
                for (const std::string spec : {"dom:3", "occ:128:4", "osm:16", "dc:4", "docc:128:4", "dom:3:8bit"})
                    for (const auto& [how, label] : paths) {
                        if (threads == 1 && how == path::tiled_cold) continue;
                        const std::string bench_name = std::string(label) + "/" + spec + "/" + name + "/" + std::to_string(res) + "/" +
                                                       (threads == 0 ? "all_threads" : "1_thread");
                        benchmark::RegisterBenchmark(bench_name.c_str(), rebuild, spec, name, res, threads, how)->Unit(benchmark::kMillisecond)->UseRealTime();
                    }
    return 0;
}();

} // namespace

BENCHMARK_MAIN();
