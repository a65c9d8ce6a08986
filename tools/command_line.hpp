#pragma once
// What the `hairshadow` commands share: the usage error (exit 2), option validators, the options of
// the commands that build maps, and the steps from a model to built maps on either back end. Each
// subcommand lives in its own <name>_command.cpp and registers itself through add_<name>_command.
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <CLI/CLI.hpp>

#include "gl_backend.hpp"

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cli {

/// A usage error: exit status 2.
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Rejects NaN and infinities (CLI11's Range lets NaN through): a non-finite option value is a usage
/// error, like any out-of-range one.
extern const CLI::Validator finite_number;
/// --wide: 0 (off) or 2 to 64 texels, as raster_options::check requires.
extern const CLI::Validator wide_line_width;

/// A registered subcommand: its CLI11 app, and what runs when it is the one given.
struct command {
    CLI::App* app;
    std::function<int()> run;
};

/// Options shared by the commands that build maps.
struct map_options {
    std::string model;
    std::string method = "dsm";
    std::string light = "dir:0,-1,-1";
    int resolution = 512;
    std::optional<float> alpha;
    float wide = 0.0f;
    float bias = 0.0f;
    bool box_filter = false;
    bool jitter = false;
    unsigned threads = 0;
    std::string backend = "cpu";
    std::string context = "egl";
    std::string gl_path; ///< --gl-path: compute, raster, or "" for compute (the default)

    bool on_gl() const { return backend == "gl"; }

    hairshadow::execution exec() const { return {threads}; }
    hairshadow::query_options query() const { return {box_filter, jitter, bias}; }
};

void add_model(CLI::App* cmd, map_options& o, bool required = true);
void add_map_options(CLI::App* cmd, map_options& o, bool with_method = true);
void add_backend_options(CLI::App* cmd, map_options& o);
void add_query_options(CLI::App* cmd, map_options& o);

/// The parsers of the library, their errors made usage errors.
hairshadow::method_spec parse_method(const std::string& text);
hairshadow::light_spec parse_light(const std::string& spec);
/// Every spec of a comma-separated list, checked before any work.
void check_method_list(const std::string& methods);
/// A procedural spec's errors as usage errors (a file's errors are not: they depend on the input).
void check_model_spec(const std::string& model);
/// A method spec for the chosen back end: the exact reference has no GL twin.
hairshadow::method_spec parse_method_for(const std::string& text, const map_options& o);
/// Loads a model; a malformed procedural spec is a usage error, a model that cannot be made is not.
hairshadow::hair_model load(const std::string& source);

double milliseconds_since(std::chrono::steady_clock::time_point start);

/// A model seen from one light, ready for any number of methods; rasterised into a fragment buffer
/// only where the exact reference of `compare` needs one.
struct lit_model {
    hairshadow::hair_model model;
    hairshadow::light_space light;
    hairshadow::raster_options raster;
    hairshadow::fragment_buffer fragments;
    double raster_ms = 0.0;
    std::unique_ptr<gl_backend> gl; ///< with --backend gl
};

/// Where a scene's model and GL context come from when not from the options (the Python module): a
/// model in memory instead of loading o.model, a context of the caller's instead of opening one.
struct scene_source {
    const hairshadow::hair_model* model = nullptr;
    hairshadow::gl::headless_context* context = nullptr;
};

/// Loads the model and fits the light; rasterises on the CPU where `cpu_fragments` (the exact
/// reference of `compare`); opens the GL context with --backend gl.
lit_model prepare_scene(const map_options& o, bool cpu_fragments, const scene_source& source = {});

/// Builds a method's maps on the CPU straight from the model (tile by tile; the exact reference
/// through a fragment buffer), for CPU queries. With `rebuild_ms`, builds twice and gives the time of
/// the second build, with the maps and working memory in place, as a renderer rebuilding every frame
/// sees it.
std::unique_ptr<hairshadow::any_shadow_map> build_map(const hairshadow::method_spec& spec, const lit_model& s, double* rebuild_ms = nullptr);

/// What a method's maps gave at a set of points.
struct method_result {
    std::vector<float> transmittance;
    double build_ms = 0.0;
    std::size_t bytes = 0;
    int layers = 0;
    std::unique_ptr<hairshadow::any_shadow_map> maps; ///< for CPU queries (read back from GL), when asked for
};

/// Builds a method on the scene's back end and queries it at `points` (by the GLSL look-up on GL).
/// With `keep_maps`, the result keeps the maps for CPU queries (on GL, read back).
method_result evaluate(const hairshadow::method_spec& spec, lit_model& s, const map_options& o, std::span<const glm::vec3> points,
                       bool keep_maps = false);

/// Writes a grey PNG of `value(x, y)` in [0, 1], top row first.
void write_grey(const std::string& path, int res, const hairshadow::execution& exec, const std::function<float(int, int)>& value);

// The subcommands, one file each.
command add_info_command(CLI::App& app, map_options& o);
command add_query_command(CLI::App& app, map_options& o);
command add_render_command(CLI::App& app, map_options& o);
command add_memory_command(CLI::App& app, map_options& o);
command add_compare_command(CLI::App& app, map_options& o);
command add_bench_command(CLI::App& app, map_options& o);
command add_animate_command(CLI::App& app, map_options& o);
command add_figure_command(CLI::App& app, map_options& o);
command add_export_command(CLI::App& app, map_options& o);

} // namespace cli
