// Full rebuilds of a method's maps from the model (rasterise and build), the old path against the new
// in one run: a reused rasterizer's fragment buffer, then the method's build from it ("buffer"),
// against the tiled build straight from the model with its run-time line walk ("tiled", AVX-512 where
// the CPU has it) and with the portable scalar walk ("tiled_scalar"); and the tiled build's cold
// first call ("tiled_cold": a new map object each time, allocation and first touch included); and
// the tiled build as it was before methods/detail/streamed_tile.hpp ("tiled_grouped": every tile's fragments
// grouped by texel, then built texel by texel), for the compositions that now stream, checked equal
// to the streamed maps before it is timed.
// Curly 1.5M (procedural:curly:strands=10000:segments=150) and Sintel, 512x512 and 2048x2048.
// Run: build/bench/hairshadow_build_bench --benchmark_filter=... --benchmark_repetitions=5
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <benchmark/benchmark.h>

#include "bench_models.hpp"

#include <map>
#include <span>
#include <vector>
#include <string>

namespace {

using namespace hairshadow;

using bench::model;

enum class path { buffer, tiled, tiled_scalar, tiled_cold };

/// The tiled build with every tile's fragments grouped by texel (detail::build_tiles), then each
/// texel built from its span: what shadow_method::build(model, ...) did for every composition before
/// the streamed build.
template <class Method>
struct grouped_build {
    typename Method::placement_type placement;
    std::vector<typename Method::texel_maps> texels;
    detail::tiled_workspace w;
    std::size_t fragments = 0;

    void operator()(const hair_model& m, const light_space& light, const raster_options& o) {
        using P = typename Method::placement_type;
        using A = typename Method::accumulation_type;
        using R = typename Method::reconstruction_type;
        w.bins.prepare(m, light, o);
        placement = P();
        placement.prepare(w.bins.extent());
        const auto res = std::size_t(light.resolution());
        texels.resize(res * res);
        fragments = detail::build_tiles(w, [&](int x, int y, std::span<const optical_fragment> in) {
            auto& out = texels[std::size_t(y) * res + std::size_t(x)];
            out = {};
            if (in.empty()) return;
            placement.prepare_texel(in, out.placement);
            R::template build<P, A>(placement, out.placement, in, out.data);
        });
    }
};

template <class Method>
void rebuild_grouped(benchmark::State& state, const std::string& name, int res, unsigned threads) {
    const auto& m = model(name);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), res);
    raster_options o;
    o.exec.threads = threads;
    grouped_build<Method> grouped;
    grouped(m, light, o);
    Method streamed;
    streamed.build(m, light, o);
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x)
            if (!(streamed.texel(x, y) == grouped.texels[std::size_t(y) * std::size_t(res) + std::size_t(x)])) {
                state.SkipWithError("the grouped build's maps differ from the streamed build's");
                return;
            }
    for (auto _ : state) grouped(m, light, o);
    state.counters["fragments/s"] = benchmark::Counter(double(grouped.fragments) * double(state.iterations()), benchmark::Counter::kIsRate);
}

using grouped_benchmark = void (*)(benchmark::State&, const std::string&, int, unsigned);
const std::map<std::string, grouped_benchmark> grouped_methods = {
    {"dom:3", rebuild_grouped<deep_opacity_maps<3>>},
    {"occ:128:4", rebuild_grouped<occupancy_maps<128, 4>>},
    {"osm:16", rebuild_grouped<opacity_shadow_maps<16>>},
    {"docc:128:4", rebuild_grouped<deep_occupancy_maps<128, 4>>},
    {"dom:3:8bit", rebuild_grouped<deep_opacity_maps_8bit<3>>},
};

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
                for (const std::string spec : {"dom:3", "occ:128:4", "osm:16", "osm:64", "dc:4", "docc:128:4", "dom:3:8bit"})
                    for (const auto& [how, label] : paths) {
                        if (threads == 1 && how == path::tiled_cold) continue;
                        const std::string bench_name = std::string(label) + "/" + spec + "/" + name + "/" + std::to_string(res) + "/" +
                                                       (threads == 0 ? "all_threads" : "1_thread");
                        benchmark::RegisterBenchmark(bench_name.c_str(), rebuild, spec, name, res, threads, how)->Unit(benchmark::kMillisecond)->UseRealTime();
                        if (how == path::tiled && grouped_methods.contains(spec)) {
                            const std::string grouped_name = "tiled_grouped" + bench_name.substr(std::string(label).size());
                            benchmark::RegisterBenchmark(grouped_name.c_str(), grouped_methods.at(spec), name, res, threads)
                                ->Unit(benchmark::kMillisecond)
                                ->UseRealTime();
                        }
                    }
    return 0;
}();

} // namespace

BENCHMARK_MAIN();
