// 07-film-scale: the exact answer for a groom of film scale. A procedural curly groom of STRANDS
// strands of SEGMENTS segments, its deep shadow map at RES x RES compressed within EPS (Lokovic &
// Veach 2000), streamed tile by tile so that no buffer of the map's fragments is ever made. Prints a
// progress bar on stderr, then the time of each step, the map's size and the process's peak memory.
//   07-film-scale [STRANDS SEGMENTS RES EPS]     (default: 20000 60 1024 0.01)
//   07-film-scale 1000000 100 4096 0.01          100M segments at 4096x4096 (issue 45's case: the map in
//                                                332 s, 5.4 GiB peak, on 2 cores; BENCHMARKS.md)
#include <hairshadow/hairshadow.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The process's peak resident memory in MiB (Linux), or -1.
double peak_mib() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
    return -1.0;
}

/// A bar of 40 characters on stderr, redrawn at each whole percent.
void show_progress(std::size_t done, std::size_t total) {
    static int shown = -1;
    const int percent = int(100 * done / total);
    if (percent == shown) return;
    shown = percent;
    std::fprintf(stderr, "\r  tiles [%-40.*s] %3d%%", percent * 40 / 100, "########################################", percent);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
}
} // namespace

int main(int argc, char** argv) {
    using namespace hairshadow;
    if (argc != 1 && argc != 5) {
        std::fprintf(stderr, "usage: 07-film-scale [STRANDS SEGMENTS RES EPS]\n");
        return 2;
    }
    try {
        const std::size_t strands = argc == 5 ? std::stoul(argv[1]) : 20000, segments = argc == 5 ? std::stoul(argv[2]) : 60;
        const int res = argc == 5 ? std::stoi(argv[3]) : 1024;
        const float eps = argc == 5 ? std::stof(argv[4]) : 0.01f;

        auto start = std::chrono::steady_clock::now();
        const hair_model model = make_procedural({.style = hair_style::curly, .strands = strands, .segments = segments, .seed = 1});
        std::printf("model: %zu segments, %zu points (%.1f s)\n", model.segment_count(), model.point_count(), seconds_since(start));

        const light_space light = light_space::fit(light_spec::directional({0, -1, -0.3f}), model.bounds(), res);
        start = std::chrono::steady_clock::now();
        const compressed_deep_shadow_map map(model, light, eps, {}, show_progress);
        const double build_s = seconds_since(start);
        std::printf("map: %dx%d, %zu fragments compressed within %g to %zu vertices, %.1f MiB (%.1f s)\n", res, res, map.fragment_count(),
                    double(eps), map.vertex_count(), double(map.memory_bytes()) / 1048576.0, build_s);
        std::printf("peak memory: %.0f MiB\n", peak_mib());
        std::printf("transmittance through the centre texel, half-way down: %.4f\n", double(map.transmittance(res / 2, res / 2, 0.5f)));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
