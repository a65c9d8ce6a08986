// The command line's measurements in Python: compare (errors against the exact map), render (the
// shaded hair as an array), bench (rebuild timings) and the temporal error of an animation.
#include "bindings.hpp"
#include "../bench_command.hpp"
#include "../compare_rows.hpp"

#include <hairshadow/io/load.hpp>
#include <hairshadow/io/obj_format.hpp>

namespace hspy {

using namespace hairshadow;

namespace {

/// The command's options from keyword arguments, the model as a Model or a path/spec; not copied or
/// moved, since `model` may point into `loaded`.
struct measured_scene {
    measured_scene() = default;
    measured_scene(const measured_scene&) = delete;
    measured_scene& operator=(const measured_scene&) = delete;

    cli::map_options options;
    std::optional<hair_model> loaded; ///< where the model was a path or spec
    const hair_model* model = nullptr;
    cli::scene_source source;
    std::optional<model_reading> reading; ///< the model's setters refuse while the call reads it
};

void set_scene(measured_scene& s, const py::object& model, const py::object& light, int resolution, const std::string& backend, const std::string& context,
               const std::string& gl_path, std::optional<float> alpha, unsigned threads) {
    auto& o = s.options;
    if (py::isinstance<py::str>(model)) {
        o.model = model.cast<std::string>();
        s.loaded = load_model(o.model);
        s.model = &*s.loaded;
    } else {
        s.model = &model.cast<const hair_model&>();
        s.reading.emplace(*s.model);
        o.model = "(a Model)";
    }
    o.light = light_text(light_of(light));
    o.resolution = resolution;
    o.alpha = alpha;
    o.threads = threads;
    if (backend != "cpu" && backend != "gl") throw argument_error("unknown backend '" + backend + "'; valid: cpu, gl");
    o.backend = backend;
    o.gl_path = gl_path;
    check_resolution(resolution);
    s.source.model = s.model;
    if (o.on_gl()) s.source.context = &gl_context(context);
}

py::list compare(const py::object& model, const std::vector<std::string>& methods, const py::object& light, int resolution, const std::string& backend,
                 const std::string& context, const std::string& gl_path, std::optional<float> alpha, float bias, bool box_filter, bool jitter, unsigned threads) {
    measured_scene s;
    set_scene(s, model, light, resolution, backend, context, gl_path, alpha, threads);
    s.options.bias = bias, s.options.box_filter = box_filter, s.options.jitter = jitter;
    std::vector<method_spec> specs;
    for (const auto& m : methods) specs.push_back(cli::parse_method_for(m, s.options));
    cli::comparison c;
    {
        py::gil_scoped_release unlocked; // GL's context is this thread's (gl_context checked it)
        c = cli::compare_methods(s.options, specs, s.source);
    }
    py::list rows;
    for (const auto& r : c.rows)
        rows.append(py::dict(py::arg("method") = r.method, py::arg("layers") = r.layers, py::arg("memory_bytes") = r.bytes, py::arg("build_ms") = r.build_ms,
                             py::arg("mean_error") = r.mean, py::arg("p95_error") = r.p95, py::arg("max_error") = r.max, py::arg("curve_error") = r.curve,
                             py::arg("image_error") = r.image_mean, py::arg("image_p99") = r.image_p99));
    return rows;
}

image render_image(const measured_scene& s, const scene& sc, const camera& cam, const method_spec& spec, const std::vector<light_space>& spaces,
                   transparency mode, float opacity, int supersample) {
    const auto exec = s.options.exec();
    raster_options ro;
    ro.exec = exec;
    ro.fixed_alpha = s.options.alpha;
    py::gil_scoped_release unlocked;
    if (s.options.on_gl()) {
        if (supersample != 1) throw argument_error("supersample needs backend='cpu'");
        return cli::gl_backend::open_on(*s.source.context, s.options.gl_path)->render_scene(sc, cam, spec, spaces, ro, mode, opacity);
    }
    std::vector<std::unique_ptr<any_shadow_map>> maps;
    std::vector<lit_light> lit;
    for (std::size_t i = 0; i < spaces.size(); ++i) {
        maps.push_back(make_shadow_map(spec));
        maps.back()->build(sc.hair, spaces[i], ro);
        lit.push_back({sc.lights[i], query_of(*maps.back(), exec), depth_shadow_map(sc.mesh, spaces[i], default_mesh_bias, exec)});
    }
    render_options options;
    options.exec = exec;
    options.supersample = supersample;
    return render_transparent(sc, cam, lit, mode, opacity, options);
}

py::array render(const py::object& model, const std::string& method, const py::object& light, int resolution, int size, float azimuth, float elevation,
                 const std::optional<std::string>& mesh, const std::vector<py::object>& fill_lights, const std::string& transparency_mode,
                 float hair_opacity, int supersample, bool srgb, const std::string& backend, const std::string& context, const std::string& gl_path,
                 std::optional<float> alpha, unsigned threads) {
    measured_scene s;
    set_scene(s, model, light, resolution, backend, context, gl_path, alpha, threads);
    const auto spec = cli::parse_method_for(method, s.options);
    camera::check_image_size(size, size);
    const auto mode = parse_transparency(transparency_mode);
    if (!(hair_opacity >= 0.0f && hair_opacity <= 1.0f)) throw argument_error("hair_opacity must be within [0, 1]");
    scene sc;
    sc.hair = *s.model;
    if (mesh) sc.mesh = read_obj(*mesh).mesh;
    else if (py::isinstance<py::str>(model) && is_procedural_spec(s.options.model)) sc.mesh = make_sphere({0, 0, 0}, parse_procedural_spec(s.options.model).head_radius, 64);
    sc.lights.push_back({light_of(light), glm::vec3(1.1f)});
    for (const auto& l : fill_lights) sc.lights.push_back({light_of(l), glm::vec3(0.45f)});
    const auto cam = camera::framing(sc.bounds(), azimuth, elevation, size, size, 1.15f);
    std::vector<light_space> spaces;
    for (const auto& l : sc.lights) spaces.push_back(light_space::fit(l.spec, sc.bounds(), resolution));
    const image picture = render_image(s, sc, cam, spec, spaces, mode, hair_opacity, supersample);
    const std::vector<py::ssize_t> shape{picture.height, picture.width, 3};
    if (srgb) {
        py::array_t<std::uint8_t> out(shape);
        const auto bytes = picture.to_srgb8();
        std::copy(bytes.begin(), bytes.end(), out.mutable_data());
        return out;
    }
    py::array_t<float> out(shape);
    std::memcpy(out.mutable_data(), picture.pixels.data(), picture.pixels.size() * sizeof(glm::vec3));
    return out;
}

py::list bench(const py::object& model, const std::vector<std::string>& methods, const py::object& light, int resolution, int repeat,
               const std::string& backend, const std::string& context, const std::string& gl_path, unsigned threads) {
    measured_scene s;
    set_scene(s, model, light, resolution, backend, context, gl_path, std::nullopt, threads);
    cli::bench_options o;
    for (const auto& m : methods) o.specs.push_back(cli::parse_method_for(m, s.options));
    o.repeat = repeat;
    o.raster.exec = s.options.exec();
    o.progress = false;
    const auto space = light_space::fit(light_of(light), s.model->bounds(), resolution);
    cli::bench_result result;
    {
        py::gil_scoped_release unlocked;
        if (s.options.on_gl()) {
            auto gl = cli::gl_backend::open_on(*s.source.context, gl_path);
            gl->set_model(*s.model);
            result = cli::measure_builds(*s.model, space, o, gl.get());
        } else {
            result = cli::measure_builds(*s.model, space, o, nullptr);
        }
    }
    py::list rows;
    for (const auto& r : result.rows)
        rows.append(py::dict(py::arg("method") = r.method, py::arg("cold_ms") = r.cold, py::arg("median_ms") = r.median, py::arg("min_ms") = r.min,
                             py::arg("max_ms") = r.max, py::arg("gpu_median_ms") = r.gpu_median, py::arg("fragments") = r.fragments,
                             py::arg("memory_bytes") = r.map_bytes, py::arg("maps_hash") = r.maps_hash,
                             py::arg("peak_mib") = r.peak_mib ? py::object(py::float_(*r.peak_mib)) : py::object(py::none()),
                             py::arg("peak_is_this_methods") = result.peak_known));
    return rows;
}

} // namespace

void bind_measures(py::module_& m) {
    m.def("compare", &compare, py::arg("model"), py::arg("methods"), py::arg("light") = "dir:0,-1,-1", py::arg("resolution") = 512, py::kw_only(),
          py::arg("backend") = "cpu", py::arg("context") = "", py::arg("gl_path") = "", py::arg("alpha") = py::none(), py::arg("bias") = 0.0f,
          py::arg("box_filter") = false, py::arg("jitter") = false, py::arg("threads") = 0u,
          "`hairshadow compare`: each method against the exact map at the model's points, along each texel's ray and in a rendered image; "
          "a list of dicts (method, layers, memory_bytes, build_ms, mean_error, p95_error, max_error, curve_error, image_error, image_p99).");
    m.def("render", &render, py::arg("model"), py::arg("method"), py::arg("light") = "dir:0,-1,-1", py::arg("resolution") = 512, py::kw_only(),
          py::arg("size") = 512, py::arg("azimuth") = 25.0f, py::arg("elevation") = 10.0f, py::arg("mesh") = py::none(),
          py::arg("fill_lights") = std::vector<py::object>{}, py::arg("transparency") = "none", py::arg("hair_opacity") = 0.4f, py::arg("supersample") = 1,
          py::arg("srgb") = false, py::arg("backend") = "cpu", py::arg("context") = "", py::arg("gl_path") = "", py::arg("alpha") = py::none(),
          py::arg("threads") = 0u,
          "`hairshadow render`: the shaded hair (and the mesh, an OBJ path, or a procedural model's head) from an orbit camera, (size, size, 3): "
          "linear RGB float32, or with srgb=True the PNG's uint8 sRGB; row 0 is the top.");
    m.def("bench", &bench, py::arg("model"), py::arg("methods"), py::arg("light") = "dir:0,-1,-1", py::arg("resolution") = 512, py::kw_only(),
          py::arg("repeat") = 10, py::arg("backend") = "cpu", py::arg("context") = "", py::arg("gl_path") = "", py::arg("threads") = 0u,
          "`hairshadow bench`: each method built once cold and `repeat` times warm from the model; a list of dicts (method, cold_ms, median_ms, "
          "min_ms, max_ms, gpu_median_ms, fragments, memory_bytes, maps_hash, peak_mib: the process's resident high-water mark while building, the "
          "interpreter's included, which bench resets before each method where Linux lets it: peak_is_this_methods).");

    py::class_<temporal_error>(m, "TemporalError", "A method's error over an animation: add each frame's transmittance and the exact one at the same points.")
        .def(py::init<>())
        .def("add_frame", [](temporal_error& t, const py::object& method, const py::object& exact) {
            const auto a = float32_array(method, "method", {-1}), b = float32_array(exact, "exact", {-1});
            t.add_frame({a.data(), std::size_t(a.shape(0))}, {b.data(), std::size_t(b.shape(0))});
        }, py::arg("method"), py::arg("exact"))
        .def_property_readonly("frames", &temporal_error::frames)
        .def_property_readonly("mean_error", &temporal_error::mean_error, "mean |T - T_exact| over points and frames")
        .def_property_readonly("flicker", &temporal_error::flicker, "mean |e(t+1) - e(t)| over points and the loop's frame pairs");
}

} // namespace hspy
