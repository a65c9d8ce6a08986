// Map build time of every published method and two hybrids from an already rasterised fragment buffer,
// on the Sintel model (171K segments) and a 1.5M-segment procedural curly model, at 512x512 and
// 2048x2048, on one thread and on all threads. Run: build/bench/hairshadow_methods_bench
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <benchmark/benchmark.h>

#include <map>
#include <string>

namespace {

using namespace hairshadow;

struct prepared {
    light_space light;
    fragment_buffer fragments;
};

const prepared& scene(const std::string& name, int res) {
    static std::map<std::string, hair_model> models;
    static std::map<std::pair<std::string, int>, prepared> cache;
    const auto key = std::make_pair(name, res);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    if (!models.count(name))
        models[name] = name == "sintel" ? read_tfx(std::string(HAIRSHADOW_SHARED_DIR) + "/data/sintel/sintel_hair.16points.tfx")
                                        : make_procedural({.style = hair_style::curly, .strands = 10000, .segments = 150, .seed = 1});
    const auto& m = models[name];
    prepared p{light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), res), {}};
    p.fragments = rasterize(m, p.light);
    return cache.emplace(key, std::move(p)).first->second;
}

void build_bench(benchmark::State& state, const std::string& spec, const std::string& model, int res, unsigned threads) {
    const auto& s = scene(model, res);
    auto map = make_shadow_map(spec);
    map->build(s.fragments, s.light, execution{threads}); // first build allocates the maps
    for (auto _ : state) map->build(s.fragments, s.light, execution{threads});
    state.counters["MiB"] = double(map->memory_bytes()) / 1048576.0;
    state.counters["fragments"] = double(s.fragments.size());
}

const int registered = [] {
    for (const std::string model : {"sintel", "curly1.5M"})
        for (int res : {512, 2048})
            for (unsigned threads : {1u, 0u})
                for (const std::string spec : {"osm:16", "osm:64", "osm:256", "dom:3", "dc:4", "occ:128:4", "adsm", "adsm:auto", "docc:128:4", "dom:3:8bit", "dsm"}) {
                    if (spec == "osm:256" && res == 2048) continue; // 4 GiB of maps
                    const std::string name = "build/" + spec + "/" + model + "/" + std::to_string(res) + "/" + (threads == 0 ? "all_threads" : "1_thread");
                    benchmark::RegisterBenchmark(name.c_str(), build_bench, spec, model, res, threads)->Unit(benchmark::kMillisecond)->UseRealTime();
                }
    return 0;
}();

} // namespace

BENCHMARK_MAIN();
