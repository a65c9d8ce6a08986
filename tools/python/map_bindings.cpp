// Shadow maps in Python: any registered method from its spec, built on the CPU (the GIL released, the
// library's threads used) or on GL, and queried into numpy arrays.
#include "bindings.hpp"
#include "map_handle.hpp"

#include <algorithm>
#include <chrono>

namespace hspy {

using namespace hairshadow;

namespace {

/// Runs f without the GIL: every call into the map's object takes its lock, and no thread may wait
/// for that lock while holding the GIL.
template <class F>
auto unlocked(F&& f) {
    py::gil_scoped_release release;
    return f();
}

py::array_t<float> query_points(shadow_map_handle& map, const py::object& points, bool box_filter, bool jitter, float bias, unsigned threads) {
    const auto p = float32_array(points, "points", {-1, 3});
    py::array_t<float> out(p.shape(0));
    const std::span<float> t(out.mutable_data(), std::size_t(p.shape(0)));
    unlocked([&] { map.transmittance(as_points(p), t, {box_filter, jitter, bias}, {threads}); });
    return out;
}

/// T (or optical depth) at texel (x, y) and each of `depths`: a curve along the texel's light ray.
py::array_t<float> along_ray(shadow_map_handle& map, int x, int y, const py::object& depths, bool optical) {
    const auto d = float32_array(depths, "depths", {-1}, dtype_rule::convert);
    py::array_t<float> out(d.shape(0));
    const std::span<const float> in(d.data(), std::size_t(d.shape(0)));
    const std::span<float> t(out.mutable_data(), std::size_t(d.shape(0)));
    unlocked([&] { map.along_ray(x, y, in, t, optical); });
    return out;
}

py::array_t<float> stored_maps(shadow_map_handle& map) {
    const auto stored = unlocked([&] { return map.stored_maps(); }); // the values and their shape from one look
    py::array_t<float> out({py::ssize_t(stored.resolution), py::ssize_t(stored.resolution), py::ssize_t(stored.k)});
    std::copy(stored.values.begin(), stored.values.end(), out.mutable_data());
    return out;
}

py::tuple fragments(shadow_map_handle& map, int x, int y) {
    auto [a, b] = unlocked([&] { return map.fragments(x, y); });
    const auto array = [](const std::vector<float>& v) {
        py::array_t<float> out(py::ssize_t(v.size()));
        std::copy(v.begin(), v.end(), out.mutable_data());
        return out;
    };
    return py::make_tuple(array(a), array(b));
}

} // namespace

void bind_maps(py::module_& m) {
    py::class_<shadow_map_handle> map(m, "ShadowMap", "Any registered method's shadow map, from its spec (see hairshadow.methods()).");
    map.def(py::init<const std::string&, const std::string&, const std::string&, const std::string&>(), py::arg("spec"), py::kw_only(),
            py::arg("backend") = "cpu", py::arg("context") = "", py::arg("gl_path") = "",
            "A method's maps, not yet built: spec as the command line's --method ('dom:3', 'occ:128:4', 'adsm:auto', 'dsm'); backend "
            "'cpu' or 'gl' (built on the module's headless GL context: context 'egl' or 'osmesa', '' for the one open, else EGL; by "
            "gl_path 'compute' or 'raster', '' for compute).");
    map.def("build", [](shadow_map_handle& h, const hair_model& model, const py::object& light, int resolution, std::optional<float> alpha,
                        float wide, unsigned threads) {
        const auto spec = light_of(light);
        const model_reading reading(model);
        unlocked([&] { h.build(model, spec, resolution, alpha, wide, threads); });
    }, py::arg("model"), py::arg("light") = "dir:0,-1,-1", py::arg("resolution") = 512, py::kw_only(), py::arg("alpha") = py::none(),
       py::arg("wide") = 0.0f, py::arg("threads") = 0u,
       "Builds the maps straight from the model for a light fitted to it (LightSpace(light, model, resolution)); alpha replaces every "
       "fragment's coverage, wide > 0 draws pre-filtered lines of that width in texels (CPU). A rebuild of the same object reuses its memory.");
    map.def("transmittance", &query_points, py::arg("points"), py::kw_only(), py::arg("box_filter") = false, py::arg("jitter") = false,
            py::arg("bias") = 0.0f, py::arg("threads") = 0u,
            "Transmittance at each of (M, 3) float32 world points, (M,) float32: 1 outside the map. On the CPU with the library's threads "
            "(the GIL released); on GL by the method's GLSL look-up (the bias too; no filter or jitter there).");
    map.def("transmittance_at", [](shadow_map_handle& h, int x, int y, const py::object& d) { return along_ray(h, x, y, d, false); },
            py::arg("x"), py::arg("y"), py::arg("depths"),
            "Transmittance at texel (x, y) and each linear depth (0..1): the curve along that texel's light ray (on GL, of the maps read back).");
    map.def("optical_depth_at", [](shadow_map_handle& h, int x, int y, const py::object& d) { return along_ray(h, x, y, d, true); },
            py::arg("x"), py::arg("y"), py::arg("depths"), "Optical depth at texel (x, y) and each linear depth.");
    map.def("maps", &stored_maps,
            "What the method stores per texel, (resolution, resolution, K) float32 indexed [y, x, k]: see map_layout (on GL, read back).");
    map.def_property_readonly("map_layout", &shadow_map_handle::map_layout, "What maps()[y, x, k] holds.");
    map.def("fragments", &fragments, py::arg("x"), py::arg("y"),
            "The exact map's ('dsm') texel (x, y): (depths, optical depth in front of and at each fragment), two (n,) float32 arrays, "
            "front to back. For a compressed exact map ('dsm:EPS'), its vertices: (depths, transmittance).");
    map.def_property_readonly("spec", &shadow_map_handle::spec_text);
    map.def_property_readonly("backend", [](const shadow_map_handle& h) { return h.on_gl() ? "gl" : "cpu"; });
    map.def_property_readonly("built", &shadow_map_handle::built);
    const auto summary = [](shadow_map_handle& h) { return unlocked([&] { return h.summary(); }); };
    map.def_property_readonly("resolution", [summary](shadow_map_handle& h) { return summary(h).light.resolution(); });
    map.def_property_readonly("light_space", [summary](shadow_map_handle& h) { return summary(h).light; }, "The LightSpace of the last build.");
    map.def_property_readonly("memory_bytes", [summary](shadow_map_handle& h) { return summary(h).memory_bytes; },
                              "Bytes of the maps (on GL, of the textures).");
    map.def_property_readonly("layer_count", [summary](shadow_map_handle& h) { return summary(h).layer_count; });
    map.def_property_readonly("fragment_count", [summary](shadow_map_handle& h) { return summary(h).fragment_count; },
                              "Fragments the last build summed (on GL: 0, they are not counted there).");
    map.def_property_readonly("maps_hash", [](shadow_map_handle& h) { return unlocked([&] { return h.maps_hash(); }); },
                              "any_shadow_map::maps_hash: equal for equal maps in any run (`hairshadow bench` prints it; on GL, of the maps read back).");
    map.def("__repr__", [](const shadow_map_handle& h) { return "<hairshadow.ShadowMap '" + h.spec_text() + "' on " + (h.on_gl() ? "gl" : "cpu") + ">"; });

    // For bench/python_crossing.py: the same query timed inside C++ alone (no array checks, no output
    // array, the GIL kept), each of `repeat` runs in milliseconds.
    m.def("_query_ms_in_cpp", [](shadow_map_handle& h, const py::object& points, int repeat, unsigned threads) {
        if (h.on_gl()) throw py::value_error("_query_ms_in_cpp times CPU maps");
        const auto p = float32_array(points, "points", {-1, 3});
        std::vector<float> out(std::size_t(p.shape(0)));
        std::vector<double> ms;
        for (int i = 0; i < repeat; ++i) {
            const auto start = std::chrono::steady_clock::now();
            h.transmittance(as_points(p), out, {}, {threads});
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        return ms;
    }, py::arg("map"), py::arg("points"), py::arg("repeat"), py::arg("threads") = 0u);
    m.def("methods", [] { return example_specs(); }, "An example spec of every registered method family and size.");
    m.def("method_grammar", &method_grammar, "The grammar of method specs.");
}

} // namespace hspy
