#pragma once
// `hairshadow bench`: how long a full rebuild of each method's maps takes on a model, for a user who
// must pick a method (see bench_command.cpp).
#include "gl_backend.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/spec.hpp>

#include <string>
#include <vector>

namespace cli {

struct bench_options {
    std::string model_name, light_name;
    std::vector<hairshadow::method_spec> specs;
    int repeat = 10;
    hairshadow::raster_options raster;
};

/// Builds each method once cold and `repeat` times warm, on the CPU (gl == nullptr) or on GL, and
/// prints a Markdown table: cold build, median, min and max rebuild, fragments per second, the maps'
/// size and the peak resident memory while building.
int run_bench(const hairshadow::hair_model& model, const hairshadow::light_space& light, const bench_options& options, gl_backend* gl);

} // namespace cli
