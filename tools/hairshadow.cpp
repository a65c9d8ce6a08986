// The `hairshadow` command: inspect hair models, build any method's shadow maps, query, render and
// compare them with the exact reference. Errors go to stderr as `error: ...` with exit status 1;
// usage errors exit 2: unknown options, bad specs, and any option value that is malformed, not finite
// or out of its range, for every command. Errors that depend on the input (a file, a light that does
// not fit the model) exit 1.

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/png.hpp>
#include <hairshadow/io/points_file.hpp>
#include <hairshadow/methods/registry.hpp>

#include <CLI/CLI.hpp>

#include "animate.hpp"
#include "bench_command.hpp"
#include "compare_table.hpp"
#include "figure.hpp"
#include "gl_backend.hpp"
#include "scene_setup.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace {

using namespace hairshadow;

/// Rejects NaN and infinities (CLI11's Range lets NaN through): a non-finite option value is a usage
/// error, like any out-of-range one.
const CLI::Validator finite_number(
    [](std::string& text) -> std::string {
        const double value = std::strtod(text.c_str(), nullptr);
        return std::isfinite(value) && std::abs(value) <= double(std::numeric_limits<float>::max()) ? std::string()
                                                                                                    : "'" + text + "' is not a finite number";
    },
    "FINITE", "finite");

/// --wide: 0 (off) or 2 to 64 texels, as raster_options::check requires.
const CLI::Validator wide_line_width(
    [](std::string& text) -> std::string {
        const double value = std::strtod(text.c_str(), nullptr);
        return value == 0.0 || (value >= 2.0 && value <= 64.0) ? std::string() : "--wide is 0 (off) or 2 to 64 texels, not " + text;
    },
    "0|[2,64]", "wide line width");

/// A usage error: exit status 2.
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
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
    std::string gl_path; ///< --gl-path: compute, raster, or "" for compute wherever the context runs it

    bool on_gl() const { return backend == "gl"; }

    execution exec() const { return {threads}; }
    query_options query() const { return {box_filter, jitter, bias}; }
};

method_spec parse_method(const std::string& text) {
    try {
        return parse_method_spec(text);
    } catch (const spec_error& e) {
        throw usage_error(e.what());
    }
}

light_spec parse_light(const std::string& spec) {
    try {
        return parse_light_spec(spec);
    } catch (const argument_error& e) {
        throw usage_error(e.what());
    }
}

/// Loads a model; a malformed procedural spec is a usage error, a model that cannot be made is not.
hair_model load(const std::string& source) {
    if (is_procedural_spec(source)) {
        procedural_options options;
        try {
            options = parse_procedural_spec(source);
        } catch (const argument_error& e) {
            throw usage_error(e.what());
        }
        return make_procedural(options);
    }
    return load_model(source);
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// A model seen from one light, ready for any number of methods; rasterised into a fragment buffer
/// only where the exact reference of `compare` needs one.
struct lit_model {
    hair_model model;
    light_space light;
    raster_options raster;
    fragment_buffer fragments;
    double raster_ms = 0.0;
    std::unique_ptr<cli::gl_backend> gl; ///< with --backend gl
};

/// Loads the model and fits the light; rasterises on the CPU where `cpu_fragments` (the exact
/// reference of `compare`); opens the GL context with --backend gl.
lit_model prepare_scene(const map_options& o, bool cpu_fragments) {
    const auto light = parse_light(o.light);
    check_resolution(o.resolution);
    if (o.on_gl() && o.wide > 0.0f) throw usage_error("--wide needs --backend cpu: core GL draws lines one pixel wide");
    if (o.on_gl() && (o.box_filter || o.jitter || o.bias != 0.0f))
        throw usage_error("--filter, --jitter and --bias are CPU queries; the GLSL look-up has none: use --backend cpu");
    if (!o.on_gl() && !o.gl_path.empty()) throw usage_error("--gl-path chooses how --backend gl builds; add --backend gl");
    lit_model s{load(o.model), {}, {}, {}, 0.0, nullptr};
    s.light = light_space::fit(light, s.model.bounds(), o.resolution);
    s.raster.exec = o.exec();
    s.raster.fixed_alpha = o.alpha;
    s.raster.wide_line_width = o.wide;
    if (cpu_fragments) {
        const auto start = std::chrono::steady_clock::now();
        s.fragments = rasterize(s.model, s.light, s.raster);
        s.raster_ms = milliseconds_since(start);
    }
    if (o.on_gl()) {
        s.gl = cli::gl_backend::open(o.context, o.gl_path);
        s.gl->set_model(s.model);
    }
    return s;
}

/// Builds a method's maps on the CPU straight from the model (tile by tile; the exact reference
/// through a fragment buffer), for CPU queries. With `rebuild_ms`, builds twice and gives the time of
/// the second build, with the maps and working memory in place, as a renderer rebuilding every frame
/// sees it.
std::unique_ptr<any_shadow_map> build_map(const method_spec& spec, const lit_model& s, double* rebuild_ms = nullptr) {
    auto map = make_shadow_map(spec);
    map->build(s.model, s.light, s.raster);
    if (rebuild_ms) {
        const auto start = std::chrono::steady_clock::now();
        map->build(s.model, s.light, s.raster);
        *rebuild_ms = milliseconds_since(start);
    }
    return map;
}

/// Writes a grey image of `value(x, y)` in [0, 1], top row first.
template <class Value>
void write_grey(const std::string& path, int res, const execution& exec, Value value) {
    std::vector<std::uint8_t> pixels(std::size_t(res) * std::size_t(res));
    parallel_for(std::size_t(res), exec, [&](std::size_t y) {
        for (int x = 0; x < res; ++x)
            pixels[(std::size_t(res) - 1 - y) * std::size_t(res) + std::size_t(x)] =
                std::uint8_t(std::lround(255.0f * std::clamp(value(x, int(y)), 0.0f, 1.0f)));
    });
    write_png(path, res, res, 1, pixels);
}

int run_info(const map_options& o) {
    if (!is_procedural_spec(o.model) && model_format_extension(o.model) == ".obj") {
        const auto contents = read_obj(o.model);
        std::printf("mesh:     %zu vertices, %zu triangles\n", contents.mesh.vertices.size(), contents.mesh.triangles.size());
        if (contents.hair.strand_count() == 0) return 0;
    }
    const auto model = load(o.model);
    const auto b = model.bounds();
    std::printf("model:    %s\n", o.model.c_str());
    if (!is_procedural_spec(o.model) && model_format_extension(o.model) == ".tfx") {
        const auto tfx = parse_tfx_file(detail::read_file_bytes(o.model), o.model);
        std::printf("format:   TressFX %d (version %g)", tfx.major_version, double(tfx.version));
        if (tfx.major_version == 3)
            std::printf(", guide strands only: %u follow hairs per guide (not grown)%s", tfx.follow_hairs_per_guide,
                        tfx.both_ends_immovable ? ", both ends immovable" : "");
        std::printf("\n");
    }
    std::printf("strands:  %zu\npoints:   %zu\nsegments: %zu\n", model.strand_count(), model.point_count(), model.segment_count());
    std::printf("bounds:   x [%.6g, %.6g]  y [%.6g, %.6g]  z [%.6g, %.6g]\n", b.min.x, b.max.x, b.min.y, b.max.y, b.min.z, b.max.z);
    std::printf("thickness: %s\n", model.thickness.empty() ? ("default " + std::to_string(model.default_thickness)).c_str() : "per point");
    std::printf("transparency: %s\ncolour: %s\n", model.transparency.empty() ? "default" : "per point", model.colors.empty() ? "default" : "per point");
    return 0;
}

/// What a method's maps gave at a set of points.
struct method_result {
    std::vector<float> transmittance;
    double build_ms = 0.0;
    std::size_t bytes = 0;
    int layers = 0;
    std::unique_ptr<any_shadow_map> maps; ///< for CPU queries (read back from GL), when asked for
};

/// Builds a method on the scene's back end and queries it at `points` (by the GLSL look-up on GL).
/// With `keep_maps`, the result keeps the maps for CPU queries (on GL, read back).
method_result evaluate(const method_spec& spec, lit_model& s, const map_options& o, std::span<const glm::vec3> points, bool keep_maps = false) {
    method_result r;
    r.transmittance.resize(points.size());
    if (s.gl) {
        r.build_ms = s.gl->build(spec, s.light, s.raster);
        r.transmittance = s.gl->transmittance(points);
        r.bytes = s.gl->memory_bytes();
        r.layers = make_shadow_map(spec)->layer_count(); // the CPU twin's, unbuilt
        if (keep_maps) r.maps = s.gl->to_cpu();
    } else {
        auto map = build_map(spec, s, &r.build_ms);
        map->transmittance(points, r.transmittance, o.query(), o.exec());
        r.bytes = map->memory_bytes();
        r.layers = map->layer_count();
        if (keep_maps) r.maps = std::move(map);
    }
    return r;
}

/// A method spec for the chosen back end: the exact reference has no GL twin.
method_spec parse_method_for(const std::string& text, const map_options& o) {
    auto spec = parse_method(text);
    if (o.on_gl() && names_exact_reference(spec)) throw usage_error("the exact reference (" + spec.text + ") is CPU-only; use --backend cpu");
    return spec;
}

int run_query(const map_options& o, const std::string& points_file) {
    const auto spec = parse_method_for(o.method, o);
    const auto points = read_points(points_file);
    auto s = prepare_scene(o, false);
    const auto t = evaluate(spec, s, o, points).transmittance;
    std::string out;
    char buf[32];
    for (float v : t) {
        std::snprintf(buf, sizeof buf, "%.6f\n", double(v));
        out += buf;
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    return 0;
}

/// What `render` draws beyond the maps: the camera's shaded view (the default) or the light's.
struct render_view {
    std::string view = "camera";
    std::string mesh;
    std::vector<std::string> fill_lights;
    float azimuth = 25.0f, elevation = 10.0f;
    int size = 512;
    std::string transparency = "none";
    float hair_opacity = 0.4f;
    std::string camera_only; ///< the first camera-view option given, if any
};

/// The shaded scene from the camera: Kajiya-Kay hair and the mesh, each light with the method's
/// maps (built on the chosen back end) and the mesh's depth map.
int run_shaded(const map_options& o, const render_view& v, const std::string& out_path) {
    const auto spec = parse_method_for(o.method, o);
    std::vector<light_spec> lights{parse_light(o.light)};
    for (const auto& l : v.fill_lights) lights.push_back(parse_light(l));
    check_resolution(o.resolution);
    camera::check_image_size(v.size, v.size);
    if (is_procedural_spec(o.model)) { // a malformed spec is a usage error, as for the other commands
        try {
            parse_procedural_spec(o.model);
        } catch (const argument_error& e) {
            throw usage_error(e.what());
        }
    }
    if (o.on_gl() && o.wide > 0.0f) throw usage_error("--wide needs --backend cpu: core GL draws lines one pixel wide");
    if (!o.on_gl() && !o.gl_path.empty()) throw usage_error("--gl-path chooses how --backend gl builds; add --backend gl");
    const auto mode = parse_transparency(v.transparency);
    if (mode != transparency::none && v.size > 4096) throw usage_error("--transparency needs --size up to 4096");
    std::fprintf(stderr, "render of %s with %s, %zu light(s), on the %s\n", o.model.c_str(), spec.text.c_str(), lights.size(), o.backend.c_str());
    const hairshadow::scene sc = cli::load_scene(o.model, v.mesh, lights);
    const auto cam = camera::framing(sc.bounds(), v.azimuth, v.elevation, v.size, v.size, 1.15f);
    raster_options ro;
    ro.exec = o.exec();
    ro.fixed_alpha = o.alpha;
    ro.wide_line_width = o.wide;
    std::vector<light_space> spaces;
    for (const auto& l : sc.lights) spaces.push_back(light_space::fit(l.spec, sc.bounds(), o.resolution));
    image picture;
    if (o.on_gl()) {
        const auto gl = cli::gl_backend::open(o.context, o.gl_path);
        picture = cli::step("building the maps and rendering on GL (transparency " + v.transparency + ")",
                            [&] { return gl->render_scene(sc, cam, spec, spaces, ro, mode, v.hair_opacity); });
        if (mode == transparency::exact) std::fprintf(stderr, "depth peeling: %d layers\n", gl->peeled_layers());
    } else {
        std::vector<std::unique_ptr<any_shadow_map>> maps;
        std::vector<lit_light> lit;
        for (std::size_t i = 0; i < spaces.size(); ++i) {
            const auto n = std::to_string(i + 1);
            maps.push_back(make_shadow_map(spec));
            cli::step("light " + n + ": building " + spec.text + " from the hair", [&] { maps.back()->build(sc.hair, spaces[i], ro); });
            auto mesh_map = cli::step("light " + n + ": the mesh's depth map", [&] { return depth_shadow_map(sc.mesh, spaces[i], default_mesh_bias, o.exec()); });
            lit.push_back({sc.lights[i], query_of(*maps.back(), o.exec()), std::move(mesh_map)});
        }
        render_options options;
        options.exec = o.exec();
        picture = cli::step("rendering (transparency " + v.transparency + ")",
                            [&] { return render_transparent(sc, cam, lit, mode, v.hair_opacity, options); });
    }
    write_png(out_path, picture.width, picture.height, 3, picture.to_srgb8());
    std::fprintf(stderr, "wrote %s (%dx%d)\n", out_path.c_str(), picture.width, picture.height);
    return 0;
}

int run_render(const map_options& o, const render_view& v, const std::string& out_path, const std::string& maps_dir) {
    if (v.view == "camera") {
        if (!maps_dir.empty()) throw usage_error("--maps needs --view light");
        return run_shaded(o, v, out_path);
    }
    if (!v.camera_only.empty()) throw usage_error(v.camera_only + " needs --view camera");
    const auto spec = parse_method_for(o.method, o);
    auto s = prepare_scene(o, false);
    std::unique_ptr<any_shadow_map> map;
    if (s.gl) {
        s.gl->build(spec, s.light, s.raster);
        map = s.gl->to_cpu(); // the maps GL built, read back
    } else {
        map = build_map(spec, s);
    }
    const int res = o.resolution;
    // The light's view: the transmittance behind the whole model (depth 1).
    write_grey(out_path, res, o.exec(), [&](int x, int y) { return map->transmittance(x, y, 1.0f); });
    std::fprintf(stderr, "wrote %s (%dx%d, %s)\n", out_path.c_str(), res, res, spec.text.c_str());
    if (!maps_dir.empty()) {
        std::filesystem::create_directories(maps_dir);
        for (int k = 0; k < map->stored_maps(); ++k) {
            char name[32];
            std::snprintf(name, sizeof name, "map_%03d.png", k);
            write_grey((std::filesystem::path(maps_dir) / name).string(), res, o.exec(),
                       [&](int x, int y) { return std::exp(-map->stored_optical_depth(x, y, k)); });
        }
        std::fprintf(stderr, "wrote %d stored maps to %s\n", map->stored_maps(), maps_dir.c_str());
    }
    return 0;
}

/// Bytes of physical memory in this machine; 0 where the system does not say.
std::size_t machine_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? std::size_t(pages) * std::size_t(page) : 0;
}

int run_memory(const map_options& o) {
    const auto spec = parse_method(o.method);
    check_resolution(o.resolution);
    if (o.model.empty()) {
        const auto bytes = make_shadow_map(spec)->memory_bytes_at(o.resolution);
        if (!bytes) throw usage_error("the exact map's size depends on the model's fragments: give a MODEL");
        std::printf("%s at %dx%d: %zu bytes (%.2f MiB)\n", spec.text.c_str(), o.resolution, o.resolution, *bytes, double(*bytes) / 1048576.0);
        // A build of maps that cannot fit fails (out of memory, exit 1); say so before anyone tries.
        if (const std::size_t machine = machine_memory_bytes(); machine > 0 && *bytes > machine)
            std::printf("the maps do not fit in this machine's memory (%.1f GiB): a build would fail\n", double(machine) / 1073741824.0);
        return 0;
    }
    const auto s = prepare_scene(o, false);
    const auto map = build_map(spec, s);
    std::printf("%s at %dx%d for %s: %zu bytes (%.2f MiB)\n", spec.text.c_str(), o.resolution, o.resolution, o.model.c_str(), map->memory_bytes(),
                double(map->memory_bytes()) / 1048576.0);
    return 0;
}

/// What compare's image error looks at: the hair alone, lit by the map's light, from the figure's
/// default camera (azimuth 25, elevation 10), 300 pixels square, supersampled 2x2; the exact map's
/// render and the pixels the hair covers.
class image_probe {
public:
    image_probe(const lit_model& s, const light_spec& light, const any_shadow_map& exact, const execution& exec) {
        sc_.hair = s.model;
        sc_.lights.push_back({light, glm::vec3(1.1f)});
        cam_ = camera::framing(sc_.hair.bounds(), 25.0f, 10.0f, 300, 300, 1.15f);
        options_.exec = exec;
        options_.supersample = 2;
        coverage_.resize(std::size_t(cam_.width) * std::size_t(cam_.height));
        exact_ = render(exact, coverage_);
    }
    image_difference operator()(const any_shadow_map& map) const { return image_error(render(map), exact_, coverage_); }

private:
    image render(const any_shadow_map& map, std::span<float> coverage = {}) const {
        const std::vector<lit_light> lights{{sc_.lights[0], query_of(map, options_.exec), {}}};
        return render_cpu(sc_, cam_, lights, options_, coverage);
    }
    hairshadow::scene sc_;
    camera cam_;
    render_options options_;
    image exact_;
    std::vector<float> coverage_;
};

int run_compare(const map_options& o, const std::string& methods, const std::string& out_dir) {
    std::vector<method_spec> specs;
    for (auto part : detail::split(methods, ',')) specs.push_back(parse_method_for(std::string(part), o));
    auto s = prepare_scene(o, true); // the exact reference is built on the CPU for either back end
    const auto exec = o.exec();
    const auto query = o.query();
    const auto exact = make_shadow_map(parse_method("dsm"));
    exact->build(s.fragments, s.light, exec);
    std::vector<float> reference(s.model.point_count());
    exact->transmittance(s.model.points, reference, query, exec);
    const image_probe images(s, parse_light(o.light), *exact, exec);
    std::vector<cli::compare_row> rows;
    for (const auto& spec : specs) {
        const auto result = evaluate(spec, s, o, s.model.points, true);
        cli::compare_row row{spec.text, result.layers, result.bytes, result.build_ms};
        cli::set_errors(row, result.transmittance, reference);
        row.curve = transmittance_curve_error(*result.maps, *exact, s.fragments, 64, exec);
        const auto seen = images(*result.maps);
        row.image_mean = seen.mean;
        row.image_p99 = seen.p99;
        rows.push_back(row);
    }
    std::ostringstream preamble;
    preamble << "Model `" << o.model << "`, light `" << o.light << "`, " << o.resolution << "x" << o.resolution << ", " << s.model.point_count()
             << " points, " << s.fragments.size() << " fragments (rasterised in " << std::lround(s.raster_ms) << " ms), " << exec.resolved()
             << " threads. ";
    if (s.gl) preamble << "Methods built on " << s.gl->description() << " and queried by their GLSL look-up; the reference on the CPU. ";
    else preamble << "Build times are CPU rebuilds straight from the model (rasterise and build, tile by tile), the second of two builds. ";
    preamble << "Errors are |T - T_exact| at the model's points; the curve error is the mean over texels of the mean |T - T_exact| "
                "from each texel's first fragment to its last (64 depths a texel); the image error is the mean and 99th percentile "
                "over hair pixels of |sRGB difference| from the exact map's render (the hair alone, 300x300, 2x2 supersampled, "
                "azimuth 25, elevation 10).";
    const auto [md, csv] = cli::format_table(rows, preamble.str());
    std::fputs(md.c_str(), stdout);
    if (!out_dir.empty()) cli::write_table(out_dir, md, csv);
    return 0;
}

int run_bench(const map_options& o, const std::string& methods, int repeat, int tile) {
    cli::bench_options b;
    for (auto part : detail::split(methods, ',')) b.specs.push_back(parse_method_for(std::string(part), o));
    auto s = prepare_scene(o, false);
    b.model_name = o.model;
    b.light_name = o.light;
    b.repeat = repeat;
    b.raster = s.raster;
    b.raster.tile_size = tile;
    return cli::run_bench(s.model, s.light, b, s.gl.get());
}

void add_model(CLI::App* cmd, map_options& o, bool required = true) {
    auto* opt = cmd->add_option("MODEL", o.model, "a .hair, .tfx, .data or .obj file, or " + std::string(procedural_grammar));
    if (required) opt->required();
}

void add_map_options(CLI::App* cmd, map_options& o, bool with_method = true) {
    if (with_method) cmd->add_option("--method", o.method, "method spec: " + method_grammar());
    cmd->add_option("--light", o.light, "light spec: " + std::string(light_grammar));
    cmd->add_option("--res", o.resolution, "shadow map resolution")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    cmd->add_option("--alpha", o.alpha, "use this alpha for every fragment instead of the strand coverage")
        ->check(finite_number & CLI::Range(0.0f, 1.0f));
    cmd->add_option("--wide", o.wide, "pre-filtered wide lines of this width in texels, 2 to 64 (Mertens et al. 3.4); 0 = aliased lines")
        ->check(finite_number & CLI::Range(0.0f, 64.0f) & wide_line_width);
}

void add_backend_options(CLI::App* cmd, map_options& o) {
    cmd->add_option("--backend", o.backend, "build the maps on the CPU or on GL (queried by the GLSL look-up)")->check(CLI::IsMember({"cpu", "gl"}));
    cmd->add_option("--context", o.context, "headless GL context for --backend gl: egl (a GPU, else Mesa) or osmesa")
        ->check(CLI::IsMember({"osmesa", "egl"}));
    cmd->add_option("--gl-path", o.gl_path,
                    "how --backend gl builds the maps: compute (compute shaders, the CPU's fragments) or raster (the papers' blended line "
                    "passes); default compute wherever the context runs it")
        ->check(CLI::IsMember({"compute", "raster"}));
}

void add_query_options(CLI::App* cmd, map_options& o) {
    cmd->add_option("--bias", o.bias, "depth bias towards the light, in linear depth units (the map's depth is 0..1)")
        ->check(finite_number & CLI::Range(-1.0f, 1.0f));
    cmd->add_flag("--filter", o.box_filter, "3x3 box filter of the optical depth (Kim & Neumann)");
    cmd->add_flag("--jitter", o.jitter, "half-texel jitter of each look-up (Sintorn & Assarsson 3.3)");
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"hairshadow: self-shadowing of hair - build, query, render and compare shadow maps"};
    app.require_subcommand(1);
    app.failure_message([](const CLI::App* command, const CLI::Error& e) {
        return "error: " + CLI::FailureMessage::simple(command, e); // as every other error is reported
    });
    map_options o;
    app.add_option("--threads", o.threads, "worker threads; 0 = all cores");

    auto* info = app.add_subcommand("info", "print a model's strand, point and segment counts and its bounds");
    add_model(info, o);

    std::string points_file;
    auto* query = app.add_subcommand("query", "print the transmittance at each point of a file of 'x y z' lines");
    add_model(query, o);
    add_map_options(query, o);
    add_query_options(query, o);
    add_backend_options(query, o);
    query->add_option("--points", points_file, "file of 'x y z' lines")->required();

    std::string out_path = "transmittance.png", maps_dir;
    render_view view;
    auto* render = app.add_subcommand("render", "write the shaded hair (or the light's view of its transmittance) as a PNG");
    add_model(render, o);
    add_map_options(render, o);
    add_backend_options(render, o);
    render->add_option("--out", out_path, "output PNG");
    render->add_option("--view", view.view, "camera: the shaded scene; light: the transmittance behind the model, from the light")
        ->check(CLI::IsMember({"camera", "light"}));
    render->add_option("--mesh", view.mesh, "an OBJ whose faces are the opaque mesh (procedural models stand on their sphere)");
    render->add_option("--fill-light", view.fill_lights, "another light, dimmer, with its own maps (repeatable)");
    render->add_option("--azimuth", view.azimuth, "camera azimuth in degrees about +y")->check(finite_number);
    render->add_option("--elevation", view.elevation, "camera elevation in degrees")->check(finite_number & CLI::Range(-89.0f, 89.0f));
    render->add_option("--size", view.size, "image size in pixels")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    render->add_option("--transparency", view.transparency,
                       "none (opaque hair), occupancy (Sintorn & Assarsson 3.4), weighted (Bavoil & Myers), exact (sorted)")
        ->check(CLI::IsMember({"none", "occupancy", "weighted", "exact"}));
    render->add_option("--hair-opacity", view.hair_opacity, "each strand's alpha over a pixel it covers, with --transparency")
        ->check(finite_number & CLI::Range(0.001f, 1.0f));
    render->add_option("--maps", maps_dir, "with --view light: also write each stored map (layer, bin or slab) as a PNG into this folder");

    auto* memory = app.add_subcommand("memory", "print the bytes a method's maps hold at a resolution");
    add_model(memory, o, false);
    add_map_options(memory, o);

    std::string methods = example_spec_list(in_compare); // the registered families' comparison examples
    std::string out_dir;
    auto* compare = app.add_subcommand("compare", "compare methods with the exact reference at the model's points");
    add_model(compare, o);
    add_map_options(compare, o, false);
    add_query_options(compare, o);
    add_backend_options(compare, o);
    compare->add_option("--methods", methods, "comma-separated method specs")->capture_default_str();
    compare->add_option("--out", out_dir, "also write compare.md and compare.csv into this folder");

    std::string bench_methods = example_spec_list(in_bench);
    int repeat = 10, tile = raster_options{}.tile_size;
    auto* bench = app.add_subcommand("bench", "time full rebuilds (rasterise and build) of each method's maps on a model: a Markdown table");
    add_model(bench, o);
    add_map_options(bench, o, false);
    add_backend_options(bench, o);
    bench->add_option("--methods", bench_methods, "comma-separated method specs")->capture_default_str();
    bench->add_option("--repeat", repeat, "rebuilds timed after the cold one, 1 to 10000")->check(CLI::Range(1, 10000));
    bench->add_option("--threads", o.threads, "worker threads; 0 = all cores");
    bench->add_option("--tile", tile,
                      "side of the CPU build's tiles, 8 to 1024 texels: larger tiles split fewer segments but hold more fragments at once "
                      "(raster_options::tile_size)")
        ->check(CLI::Range(8, 1024));

    cli::animate_options anim;
    std::string motion = "both";
    auto* animate = app.add_subcommand("animate", "the methods side by side over frames of swaying hair and an orbiting light: "
                                                  "an animated PNG (and MP4 with ffmpeg) and a table of error and flicker over time");
    animate->add_option("MODEL", anim.model, "a .hair, .tfx, .data or .obj file, or " + std::string(procedural_grammar))->required();
    animate->add_option("--mesh", anim.mesh, "an OBJ whose faces are the opaque mesh (e.g. the Sintel head)");
    animate->add_option("--light", anim.light, "the light at the first frame: " + std::string(light_grammar));
    animate->add_option("--methods", anim.methods, "comma-separated method specs; the exact reference is always the last panel")->capture_default_str();
    animate->add_option("--frames", anim.frames, "frames, 1 to 1000")->check(CLI::Range(1, 1000));
    animate->add_option("--fps", anim.fps, "frames per second, 1 to 100")->check(CLI::Range(1, 100));
    animate->add_option("--motion", motion, "sway (the hair), light (an orbit) or both")->check(CLI::IsMember({"sway", "light", "both"}));
    animate->add_option("--amplitude", anim.amplitude, "the sway's largest turn of a strand's tip, 0 to 90 degrees")
        ->check(finite_number & CLI::Range(0.0f, 90.0f));
    animate->add_option("--seed", anim.seed, "the sway's seed");
    animate->add_option("--res", anim.resolution, "shadow map resolution")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    animate->add_option("--size", anim.size, "panel size in pixels, 16 to 1024")->check(CLI::Range(16, 1024));
    animate->add_option("--supersample", anim.supersample, "render each panel at N x N samples a pixel, 1 to 4")->check(CLI::Range(1, 4));
    animate->add_option("--azimuth", anim.azimuth, "camera azimuth in degrees about +y")->check(finite_number);
    animate->add_option("--elevation", anim.elevation, "camera elevation in degrees")->check(finite_number & CLI::Range(-89.0f, 89.0f));
    animate->add_option("--out", anim.out, "output folder");
    animate->add_flag("--full-colour", anim.full_colour, "write the animated PNG in full colour, not in one 256-colour palette (a larger file)");

    cli::figure_options fig;
    auto* figure = app.add_subcommand("figure", "the comparison figure: shaded hair with each method, crops, error heat maps, ray plots, table");
    figure->add_option("--model", fig.model, "a model file or " + std::string(procedural_grammar) + " (procedural models stand on their sphere)");
    figure->add_option("--mesh", fig.mesh, "an OBJ whose faces are the opaque mesh (e.g. the Sintel head)");
    figure->add_option("--light", fig.light, "light spec: " + std::string(light_grammar));
    figure->add_option("--methods", fig.methods, "comma-separated method specs between 'no shadows' and the exact reference")->capture_default_str();
    figure->add_option("--res", fig.resolution, "shadow map resolution")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    figure->add_option("--size", fig.size, "panel size in pixels")->check(CLI::Range(16, 4096));
    figure->add_option("--supersample", fig.supersample, "render each panel at N x N samples a pixel (1 to 8; --size times N at most 8192)")
        ->check(CLI::Range(1, 8));
    figure->add_option("--azimuth", fig.azimuth, "camera azimuth in degrees about +y")->check(finite_number);
    figure->add_option("--elevation", fig.elevation, "camera elevation in degrees")->check(finite_number & CLI::Range(-89.0f, 89.0f));
    figure->add_option("--out", fig.out, "output folder");
    float figure_opacity = 0.0f;
    figure->add_option("--transparency", figure_opacity,
                       "instead: the transparency figure (exact, occupancy-ordered, weighted, opaque) with this hair opacity")
        ->check(finite_number & CLI::Range(0.001f, 1.0f));

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    for (const char* name : {"--mesh", "--fill-light", "--azimuth", "--elevation", "--size", "--transparency", "--hair-opacity"})
        if (render->count(name) > 0 && view.camera_only.empty()) view.camera_only = name;
    try {
        if (*info) return run_info(o);
        if (*query) return run_query(o, points_file);
        if (*render) return run_render(o, view, out_path, maps_dir);
        if (*memory) return run_memory(o);
        if (*compare) return run_compare(o, methods, out_dir);
        if (*bench) return run_bench(o, bench_methods, repeat, tile);
        if (*animate) {
            try { // everything a usage error can be, before any work
                check_resolution(anim.resolution);
                if (is_procedural_spec(anim.model)) parse_procedural_spec(anim.model);
            } catch (const argument_error& e) {
                throw usage_error(e.what());
            }
            for (auto part : detail::split(anim.methods, ',')) parse_method(std::string(part));
            parse_light(anim.light);
            anim.motion = motion == "sway" ? cli::motion_kind::sway : motion == "light" ? cli::motion_kind::light : cli::motion_kind::both;
            anim.exec = o.exec();
            return cli::run_animate(anim);
        }
        if (*figure) {
            try { // everything a usage error can be, before any work
                check_resolution(fig.resolution);
                if (is_procedural_spec(fig.model)) parse_procedural_spec(fig.model);
                if (fig.size * fig.supersample > 8192) throw argument_error("--size times --supersample must be at most 8192 pixels");
            } catch (const argument_error& e) {
                throw usage_error(e.what());
            }
            for (auto part : detail::split(fig.methods, ',')) parse_method(std::string(part));
            parse_light(fig.light);
            fig.exec = o.exec();
            return figure_opacity > 0.0f ? cli::run_transparency_figure(fig, figure_opacity) : cli::run_figure(fig);
        }
    } catch (const usage_error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 2;
}
