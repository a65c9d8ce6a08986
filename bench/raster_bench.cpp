// Rasterisation throughput (fragments per second) and exact-reference build time on the Sintel model
// (171K segments) and a 1.5M-segment procedural curly model, at 512x512 and 2048x2048, on one thread
// and on all threads. Run: build/bench/hairshadow_bench --benchmark_filter=...
#include <hairshadow/hairshadow.hpp>

#include <benchmark/benchmark.h>

#include "bench_models.hpp"

#include <map>
#include <string>

namespace {

using namespace hairshadow;

using bench::model;

/// `reuse`: one rasterizer across iterations, as a renderer rebuilding its maps every frame would keep
/// it; otherwise the one-shot rasterize(), which allocates (and first touches) its memory every time.
void rasterize_bench(benchmark::State& state, const std::string& name, int res, unsigned threads, bool reuse) {
    const auto& m = model(name);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), res);
    raster_options o;
    o.exec.threads = threads;
    rasterizer reused(o);
    if (reuse) reused(m, light); // warm up: the first call allocates the workspace
    std::size_t fragments = 0;
    for (auto _ : state) {
        if (reuse) {
            fragments = reused(m, light).size();
        } else {
            auto fb = rasterize(m, light, o);
            fragments = fb.size();
            benchmark::DoNotOptimize(fb);
        }
    }
    state.counters["fragments"] = double(fragments);
    state.counters["fragments/s"] = benchmark::Counter(double(fragments) * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["segments/s"] = benchmark::Counter(double(m.segment_count()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void reference_bench(benchmark::State& state, const std::string& name, int res, unsigned threads) {
    const auto& m = model(name);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), res);
    raster_options o;
    o.exec.threads = threads;
    const auto fb = rasterize(m, light, o);
    for (auto _ : state) {
        deep_shadow_map dsm(fb, light, o.exec);
        benchmark::DoNotOptimize(dsm);
    }
    state.counters["fragments"] = double(fb.size());
}

const int registered = [] {
    for (const std::string name : {"sintel", "curly1.5M"})
        for (int res : {512, 2048})
            for (unsigned threads : {1u, 0u}) {
                const std::string suffix = name + "/" + std::to_string(res) + "/" + (threads == 0 ? "all_threads" : "1_thread");
                benchmark::RegisterBenchmark(("rasterize/one_shot/" + suffix).c_str(), rasterize_bench, name, res, threads, false)
                    ->Unit(benchmark::kMillisecond)->UseRealTime();
                benchmark::RegisterBenchmark(("rasterize/reused/" + suffix).c_str(), rasterize_bench, name, res, threads, true)
                    ->Unit(benchmark::kMillisecond)->UseRealTime();
                benchmark::RegisterBenchmark(("exact_reference/" + suffix).c_str(), reference_bench, name, res, threads)
                    ->Unit(benchmark::kMillisecond)->UseRealTime();
            }
    return 0;
}();

} // namespace

BENCHMARK_MAIN();
