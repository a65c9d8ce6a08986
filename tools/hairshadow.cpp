// The `hairshadow` command: inspect hair models, query and render light-space transmittance.
// Errors go to stderr as `error: ...` with exit status 1; usage errors exit 2.

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/png.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <variant>

namespace {

using namespace hairshadow;

/// A usage error: exit status 2.
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

constexpr std::string_view method_grammar = "dsm (exact) | dsm:EPS (Lokovic-Veach compression, 0 < EPS < 1)";

/// The exact map, or its compression.
struct reference_method {
    std::optional<float> tolerance;
};

reference_method parse_method(const std::string& spec) {
    const auto parts = detail::split(spec, ':');
    if (parts[0] == "dsm" && parts.size() == 1) return {};
    if (parts[0] == "dsm" && parts.size() == 2) {
        float eps = 0;
        try {
            eps = detail::parse_number<float>(parts[1], "tolerance");
        } catch (const argument_error&) {
            throw usage_error("bad method spec '" + spec + "'; valid: " + std::string(method_grammar));
        }
        if (eps > 0.0f && eps < 1.0f) return {eps};
    }
    throw usage_error("bad method spec '" + spec + "'; valid: " + std::string(method_grammar));
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

struct common_options {
    std::string model;
    std::string method = "dsm";
    std::string light = "dir:0,-1,-1";
    int resolution = 512;
    std::optional<float> alpha;
    float wide = 0.0f;
    unsigned threads = 0;
};

struct built_map {
    light_space light;
    std::unique_ptr<deep_shadow_map> exact;
    std::unique_ptr<compressed_deep_shadow_map> compressed;

    float transmittance(int x, int y, float depth) const {
        return compressed ? compressed->transmittance(x, y, depth) : exact->transmittance(x, y, depth);
    }
    float transmittance(const glm::vec3& p, float bias) const {
        return compressed ? compressed->transmittance(p, bias) : exact->transmittance(p, bias);
    }
};

built_map build(const common_options& o, const hair_model& model) {
    const auto method = parse_method(o.method);
    const auto light = parse_light(o.light);
    check_resolution(o.resolution);
    raster_options ro;
    ro.exec.threads = o.threads;
    ro.fixed_alpha = o.alpha;
    ro.wide_line_width = o.wide;
    built_map map{light_space::fit(light, model.bounds(), o.resolution), nullptr, nullptr};
    const auto fragments = rasterize(model, map.light, ro);
    map.exact = std::make_unique<deep_shadow_map>(fragments, map.light, ro.exec);
    if (method.tolerance) map.compressed = std::make_unique<compressed_deep_shadow_map>(*map.exact, *method.tolerance, ro.exec);
    return map;
}

std::vector<glm::vec3> read_points(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw io_error(path, "cannot open for reading");
    std::vector<glm::vec3> points;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::istringstream fields(line);
        std::string token;
        glm::vec3 p;
        int count = 0;
        while (fields >> token) {
            if (count == 3) throw io_error(path, "line " + std::to_string(number) + ": more than three numbers");
            try {
                p[count++] = detail::parse_number<float>(token, "coordinate");
            } catch (const argument_error& e) {
                throw io_error(path, "line " + std::to_string(number) + ": " + e.what());
            }
        }
        if (count != 3) throw io_error(path, "line " + std::to_string(number) + ": expected three numbers 'x y z'");
        points.push_back(p);
    }
    if (in.bad()) throw io_error(path, "read failed");
    return points;
}

int run_info(const common_options& o) {
    if (!is_procedural_spec(o.model) && std::filesystem::path(o.model).extension() == ".obj") {
        const auto contents = read_obj(o.model);
        std::printf("mesh:     %zu vertices, %zu triangles\n", contents.mesh.vertices.size(), contents.mesh.triangles.size());
        if (contents.hair.strand_count() == 0) return 0;
    }
    const auto model = load(o.model);
    const auto b = model.bounds();
    std::printf("model:    %s\n", o.model.c_str());
    std::printf("strands:  %zu\npoints:   %zu\nsegments: %zu\n", model.strand_count(), model.point_count(), model.segment_count());
    std::printf("bounds:   x [%.6g, %.6g]  y [%.6g, %.6g]  z [%.6g, %.6g]\n", b.min.x, b.max.x, b.min.y, b.max.y, b.min.z, b.max.z);
    std::printf("thickness: %s\n", model.thickness.empty() ? ("default " + std::to_string(model.default_thickness)).c_str() : "per point");
    std::printf("transparency: %s\ncolour: %s\n", model.transparency.empty() ? "default" : "per point", model.colors.empty() ? "default" : "per point");
    return 0;
}

int run_query(const common_options& o, const std::string& points_file, float bias) {
    const auto points = read_points(points_file);
    const auto model = load(o.model);
    const auto map = build(o, model);
    std::string out;
    out.reserve(points.size() * 10);
    char buf[32];
    for (const auto& p : points) {
        std::snprintf(buf, sizeof buf, "%.6f\n", double(map.transmittance(p, bias)));
        out += buf;
    }
    std::fwrite(out.data(), 1, out.size(), stdout);
    return 0;
}

int run_render(const common_options& o, const std::string& out_path) {
    const auto model = load(o.model);
    const auto map = build(o, model);
    const int res = o.resolution;
    std::vector<std::uint8_t> pixels(std::size_t(res) * std::size_t(res));
    // The light's view: transmittance behind the whole model (depth 1), top row first.
    parallel_for(std::size_t(res), execution{o.threads}, [&](std::size_t y) {
        for (int x = 0; x < res; ++x) {
            const float t = map.transmittance(x, int(y), 1.0f);
            pixels[(std::size_t(res) - 1 - y) * std::size_t(res) + std::size_t(x)] = std::uint8_t(std::lround(255.0f * std::clamp(t, 0.0f, 1.0f)));
        }
    });
    write_png(out_path, res, res, 1, pixels);
    std::fprintf(stderr, "wrote %s (%dx%d, %s)\n", out_path.c_str(), res, res, o.method.c_str());
    return 0;
}

void add_map_options(CLI::App* cmd, common_options& o) {
    cmd->add_option("MODEL", o.model, "a .hair, .tfx, .data or .obj file, or " + std::string(procedural_grammar))->required();
    cmd->add_option("--method", o.method, "method spec: " + std::string(method_grammar));
    cmd->add_option("--light", o.light, "light spec: " + std::string(light_grammar));
    cmd->add_option("--res", o.resolution, "shadow map resolution, 1.." + std::to_string(HAIRSHADOW_MAX_RESOLUTION));
    cmd->add_option("--alpha", o.alpha, "use this alpha for every fragment instead of the strand coverage")->check(CLI::Range(0.0f, 1.0f));
    cmd->add_option("--wide", o.wide, "pre-filtered wide lines of this width in texels (Mertens et al. 3.4); 0 = aliased lines")
        ->check(CLI::Range(0.0f, 64.0f));
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"hairshadow: self-shadowing of hair - inspect models, query and render light-space transmittance"};
    app.require_subcommand(1);
    common_options o;
    app.add_option("--threads", o.threads, "worker threads; 0 = all cores");

    auto* info = app.add_subcommand("info", "print a model's strand, point and segment counts and its bounds");
    info->add_option("MODEL", o.model, "a model file or procedural spec")->required();

    std::string points_file;
    float bias = 0.0f;
    auto* query = app.add_subcommand("query", "print the transmittance at each point of a file of 'x y z' lines");
    add_map_options(query, o);
    query->add_option("--points", points_file, "file of 'x y z' lines")->required();
    query->add_option("--bias", bias, "depth bias towards the light, in linear depth units");

    std::string out_path = "transmittance.png";
    auto* render = app.add_subcommand("render", "write the light's view of the transmittance behind the model as a PNG");
    add_map_options(render, o);
    render->add_option("--out", out_path, "output PNG");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    try {
        if (*info) return run_info(o);
        if (*query) return run_query(o, points_file, bias);
        if (*render) return run_render(o, out_path);
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
