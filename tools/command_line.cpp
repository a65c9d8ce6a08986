// What the `hairshadow` commands share (command_line.hpp).
#include "command_line.hpp"

#include <hairshadow/io/load.hpp>
#include <hairshadow/io/png.hpp>

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace cli {

using namespace hairshadow;

const CLI::Validator finite_number(
    [](std::string& text) -> std::string {
        const double value = std::strtod(text.c_str(), nullptr);
        return std::isfinite(value) && std::abs(value) <= double(std::numeric_limits<float>::max()) ? std::string()
                                                                                                    : "'" + text + "' is not a finite number";
    },
    "FINITE", "finite");

const CLI::Validator wide_line_width(
    [](std::string& text) -> std::string {
        const double value = std::strtod(text.c_str(), nullptr);
        return value == 0.0 || (value >= 2.0 && value <= 64.0) ? std::string() : "--wide is 0 (off) or 2 to 64 texels, not " + text;
    },
    "0|[2,64]", "wide line width");

void add_model(CLI::App* cmd, map_options& o, bool required) {
    auto* opt = cmd->add_option("MODEL", o.model, "a .hair, .tfx, .data or .obj file, or " + std::string(procedural_grammar));
    if (required) opt->required();
}

void add_map_options(CLI::App* cmd, map_options& o, bool with_method) {
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
                    "passes); default compute (OpenGL 4.3 core, no extension)")
        ->check(CLI::IsMember({"compute", "raster"}));
}

void add_query_options(CLI::App* cmd, map_options& o) {
    cmd->add_option("--bias", o.bias, "depth bias towards the light, in linear depth units (the map's depth is 0..1)")
        ->check(finite_number & CLI::Range(-1.0f, 1.0f));
    cmd->add_flag("--filter", o.box_filter, "3x3 box filter of the optical depth (Kim & Neumann)");
    cmd->add_flag("--jitter", o.jitter, "half-texel jitter of each look-up (Sintorn & Assarsson 3.3)");
}

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

void check_method_list(const std::string& methods) {
    for (auto part : detail::split(methods, ',')) parse_method(std::string(part));
}

void check_model_spec(const std::string& model) {
    if (!is_procedural_spec(model)) return;
    try {
        parse_procedural_spec(model);
    } catch (const argument_error& e) {
        throw usage_error(e.what());
    }
}

method_spec parse_method_for(const std::string& text, const map_options& o) {
    auto spec = parse_method(text);
    if (o.on_gl() && names_exact_reference(spec)) throw usage_error("the exact reference (" + spec.text + ") is CPU-only; use --backend cpu");
    return spec;
}

hair_model load(const std::string& source) {
    if (!is_procedural_spec(source)) return load_model(source);
    check_model_spec(source);
    return make_procedural(parse_procedural_spec(source));
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

lit_model prepare_scene(const map_options& o, bool cpu_fragments, const scene_source& source) {
    const auto light = parse_light(o.light);
    check_resolution(o.resolution);
    if (o.on_gl() && o.wide > 0.0f) throw usage_error("--wide needs --backend cpu: core GL draws lines one pixel wide");
    if (o.on_gl() && (o.box_filter || o.jitter))
        throw usage_error("--filter and --jitter are CPU queries; the GLSL look-up has neither: use --backend cpu");
    if (!o.on_gl() && !o.gl_path.empty()) throw usage_error("--gl-path chooses how --backend gl builds; add --backend gl");
    lit_model s{source.model ? *source.model : load(o.model), {}, {}, {}, 0.0, nullptr};
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
        s.gl = source.context ? gl_backend::open_on(*source.context, o.gl_path) : gl_backend::open(o.context, o.gl_path);
        s.gl->set_model(s.model);
    }
    return s;
}

std::unique_ptr<any_shadow_map> build_map(const method_spec& spec, const lit_model& s, double* rebuild_ms) {
    auto map = make_shadow_map(spec);
    map->build(s.model, s.light, s.raster);
    if (rebuild_ms) {
        const auto start = std::chrono::steady_clock::now();
        map->build(s.model, s.light, s.raster);
        *rebuild_ms = milliseconds_since(start);
    }
    return map;
}

method_result evaluate(const method_spec& spec, lit_model& s, const map_options& o, std::span<const glm::vec3> points, bool keep_maps) {
    method_result r;
    r.transmittance.resize(points.size());
    if (s.gl) {
        r.build_ms = s.gl->build(spec, s.light, s.raster);
        r.transmittance = s.gl->transmittance(points, o.bias);
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

void write_grey(const std::string& path, int res, const execution& exec, const std::function<float(int, int)>& value) {
    std::vector<std::uint8_t> pixels(std::size_t(res) * std::size_t(res));
    parallel_for(std::size_t(res), exec, [&](std::size_t y) {
        for (int x = 0; x < res; ++x)
            pixels[(std::size_t(res) - 1 - y) * std::size_t(res) + std::size_t(x)] =
                std::uint8_t(std::lround(255.0f * std::clamp(value(x, int(y)), 0.0f, 1.0f)));
    });
    write_png(path, res, res, 1, pixels);
}

} // namespace cli
