#pragma once
// `hairshadow bench`: how long a full rebuild of each method's maps takes on a model, for a user who
// must pick a method (see bench_command.cpp).
#include "gl_backend.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/spec.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace cli {

struct bench_options {
    std::string model_name, light_name;
    std::vector<hairshadow::method_spec> specs;
    int repeat = 10;
    hairshadow::raster_options raster;
    bool progress = true; ///< each method's name and median on stderr as it goes
};

/// One method's timings.
struct bench_row {
    std::string method;
    double cold = 0, median = 0, min = 0, max = 0, gpu_median = 0; ///< gpu_median: by GL timer queries
    std::size_t fragments = 0, map_bytes = 0;
    std::uint64_t maps_hash = 0; ///< any_shadow_map::maps_hash of the last build (on GL, of its read-back)
    std::optional<double> peak_mib;
};

struct bench_result {
    std::vector<bench_row> rows;
    bool peak_known = false;             ///< whether the peaks are each method's (else the whole run's)
    std::optional<double> baseline_kib;  ///< resident memory before the first build
};

/// Builds each method once cold and `repeat` times warm, on the CPU (gl == nullptr) or on GL.
bench_result measure_builds(const hairshadow::hair_model& model, const hairshadow::light_space& light, const bench_options& options, gl_backend* gl);

/// Builds each method once cold and `repeat` times warm, on the CPU (gl == nullptr) or on GL, and
/// prints a Markdown table: cold build, median, min and max rebuild, fragments per second, the maps'
/// size and the peak resident memory while building.
int run_bench(const hairshadow::hair_model& model, const hairshadow::light_space& light, const bench_options& options, gl_backend* gl);

} // namespace cli
