// `hairshadow bench`: full rebuilds of each method's maps from the model (rasterise and build), timed
// on the CPU or on GL. Peak memory is the process's resident high-water mark (Linux VmHWM), reset
// before each method, so it counts the model and everything the build holds.
#include "bench_command.hpp"
#include "command_line.hpp"

#include <hairshadow/methods/registry.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace cli {
namespace {

using namespace hairshadow;

double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

/// A field of /proc/self/status in kB ("VmHWM", "VmRSS"), or nothing off Linux.
std::optional<double> status_kib(const std::string& field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1));
    return std::nullopt;
}

/// Starts a new high-water mark at the present resident size, having handed freed memory back
/// first; false where the system cannot (then the peak is the whole run's).
bool reset_peak() {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.flush();
    return clear.good();
}

} // namespace

bench_result measure_builds(const hair_model& model, const light_space& light, const bench_options& o, gl_backend* gl) {
    const auto now = [] { return std::chrono::steady_clock::now(); };
    // GL counts no fragments: they are the CPU rule's, counted once, tile by tile.
    const std::size_t gl_fragments = gl ? count_fragments(model, light, o.raster) : 0;
    if (o.repeat < 1) throw argument_error("bench: repeat must be at least 1, not " + std::to_string(o.repeat));
    bench_result result;
    result.peak_known = reset_peak();
    result.baseline_kib = status_kib("VmRSS");
    auto& rows = result.rows;
    for (const auto& spec : o.specs) {
        if (o.progress) std::fprintf(stderr, "  %s ...", spec.text.c_str());
        if (o.progress) std::fflush(stderr);
        bench_row r;
        r.method = spec.text;
        result.peak_known = reset_peak() && result.peak_known;
        std::vector<double> times;
        if (gl) {
            // The first build compiles the driver's shader variants: it is the cold one.
            const auto start = now();
            gl->build(spec, light, o.raster); // builds twice
            r.cold = ms_between(start, now());
            std::vector<double> gpu;
            for (int i = 0; i < o.repeat; ++i) {
                times.push_back(gl->rebuild(light, o.raster));
                gpu.push_back(gl->last_gpu_ms());
            }
            std::sort(gpu.begin(), gpu.end());
            r.gpu_median = gpu.size() % 2 ? gpu[gpu.size() / 2] : 0.5 * (gpu[gpu.size() / 2 - 1] + gpu[gpu.size() / 2]);
            r.map_bytes = gl->memory_bytes();
            r.fragments = gl_fragments;
            r.maps_hash = gl->to_cpu()->maps_hash();
        } else {
            auto map = make_shadow_map(spec);
            auto start = now();
            map->build(model, light, o.raster);
            r.cold = ms_between(start, now());
            for (int i = 0; i < o.repeat; ++i) {
                start = now();
                map->build(model, light, o.raster);
                times.push_back(ms_between(start, now()));
            }
            r.map_bytes = map->memory_bytes();
            r.fragments = map->fragment_count();
            r.maps_hash = map->maps_hash();
        }
        if (const auto hwm = status_kib("VmHWM")) r.peak_mib = *hwm / 1024.0; // before the hash, which reads back GL's maps
        std::sort(times.begin(), times.end());
        r.min = times.front();
        r.max = times.back();
        r.median = times.size() % 2 ? times[times.size() / 2] : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
        if (o.progress) std::fprintf(stderr, " %.1f ms\n", r.median);
        rows.push_back(r);
    }
    return result;
}

int run_bench(const hair_model& model, const light_space& light, const bench_options& o, gl_backend* gl) {
    const auto [rows, peak_known, baseline_kib] = measure_builds(model, light, o, gl);
    std::printf("Model `%s` (%zu strands, %zu segments), light `%s`, %dx%d, %u threads, ", o.model_name.c_str(), model.strand_count(),
                model.segment_count(), o.light_name.c_str(), light.resolution(), light.resolution(), o.raster.exec.resolved());
    if (gl) std::printf("built on %s. ", gl->description().c_str());
    else
        std::printf("built on the CPU, tile by tile (tiles of %d texels, %s line walk). ", o.raster.tile_size,
                    resolve(o.raster.instructions) == instruction_set::avx512 ? "AVX-512" : "scalar");
    std::printf("A rebuild is a full build from the model (rasterise and build), the maps and working memory already in place; "
                "the cold build is the first, which also allocates them%s. Times over %d rebuilds; peak memory is the process's resident "
                "high-water mark while building%s; the maps hash is any_shadow_map::maps_hash, the same for the same maps in any run",
                gl ? " and compiles the driver's shaders" : "", o.repeat, peak_known ? ", model included" : " (not resettable here: the whole run's)");
    if (baseline_kib) std::printf(" (%.0f MiB resident before the first build)", *baseline_kib / 1024.0);
    std::printf(".\n\n");
    std::printf("| method | cold (ms) | median (ms) |%s min (ms) | max (ms) | fragments/s | maps (MiB) | peak memory (MiB) | maps hash |\n",
                gl ? " GPU median (ms) |" : "");
    std::printf("|---|---|---|%s---|---|---|---|---|---|\n", gl ? "---|" : "");
    for (const auto& r : rows) {
        std::printf("| %s | %.1f | %.1f | ", r.method.c_str(), r.cold, r.median);
        if (gl) std::printf("%.2f | ", r.gpu_median);
        std::printf("%.1f | %.1f | %.0f M | %.1f | ", r.min, r.max,
                    r.median > 0 ? double(r.fragments) / (r.median * 1e3) : 0.0, double(r.map_bytes) / 1048576.0);
        if (r.peak_mib) std::printf("%.0f | ", *r.peak_mib);
        else std::printf("- | ");
        std::printf("%016llx |\n", static_cast<unsigned long long>(r.maps_hash));
    }
    if (gl && o.specs.size() >= 2) {
        // Several methods for one light: a light pass each, against one shared, alternated so that
        // both see the same machine.
        std::vector<double> separate, shared;
        gl->build_all(o.specs, light, o.raster, false); // makes the maps and compiles the driver's variants
        gl->build_all(o.specs, light, o.raster, true);
        for (int i = 0; i < o.repeat; ++i) {
            separate.push_back(gl->build_all(o.specs, light, o.raster, false));
            shared.push_back(gl->build_all(o.specs, light, o.raster, true));
        }
        const auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
        };
        const double a = median(separate), b = median(shared);
        std::printf("\nAll %zu methods for this light, medians of %d: with a light pass each %.1f ms; sharing one gl::light_pass %.1f ms "
                    "(%.1f ms saved, %.2fx).\n",
                    o.specs.size(), o.repeat, a, b, a - b, b > 0 ? a / b : 0.0);
    }
    return 0;
}

namespace {
struct bench_args {
    std::string methods = example_spec_list(in_bench); // the registered families' bench examples
    int repeat = 10;
    int tile = raster_options{}.tile_size;
};

int run_bench_command(const map_options& o, const bench_args& a) {
    bench_options b;
    for (auto part : detail::split(a.methods, ',')) b.specs.push_back(parse_method_for(std::string(part), o));
    auto s = prepare_scene(o, false);
    b.model_name = o.model;
    b.light_name = o.light;
    b.repeat = a.repeat;
    b.raster = s.raster;
    b.raster.tile_size = a.tile;
    return run_bench(s.model, s.light, b, s.gl.get());
}
} // namespace

command add_bench_command(CLI::App& app, map_options& o) {
    auto a = std::make_shared<bench_args>();
    auto* cmd = app.add_subcommand("bench", "time full rebuilds (rasterise and build) of each method's maps on a model: a Markdown table");
    add_model(cmd, o);
    add_map_options(cmd, o, false);
    add_backend_options(cmd, o);
    cmd->add_option("--methods", a->methods, "comma-separated method specs")->capture_default_str();
    cmd->add_option("--repeat", a->repeat, "rebuilds timed after the cold one, 1 to 10000")->check(CLI::Range(1, 10000));
    cmd->add_option("--threads", o.threads, "worker threads; 0 = all cores");
    cmd->add_option("--tile", a->tile,
                    "side of the CPU build's tiles, 8 to 1024 texels: larger tiles split fewer segments but hold more fragments at once "
                    "(raster_options::tile_size)")
        ->check(CLI::Range(8, 1024));
    return {cmd, [&o, a] { return run_bench_command(o, *a); }};
}

} // namespace cli
