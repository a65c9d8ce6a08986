#pragma once
// What the Python module's files share: numpy arrays checked and viewed as the library's spans, the
// light given as a spec or a Light, and the headless GL context the module opens once.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/methods/registry.hpp>

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hairshadow::gl {
class headless_context;
class any_gl_shadow_map;
class hair_mesh;
}

namespace hspy {

namespace py = pybind11;

/// A C-contiguous float32 array, as numpy gives it.
using float_array = py::array_t<float, py::array::c_style>;

/// How float32_array takes an array of another dtype.
enum class dtype_rule {
    strict,  ///< a TypeError: for points and per-point arrays, where a silent conversion would copy a large array
    convert, ///< any real dtype converted: for small arguments (a vector, a few depths)
};

/// `value` as a C-contiguous float32 array of `shape` (-1: any length), for argument `name`: a float32
/// array is used as it is (copied only where not contiguous), a list or tuple is converted; an array
/// of another dtype is a TypeError (or converted, by `rule`), and a wrong shape a ValueError, each
/// naming what was expected.
float_array float32_array(const py::handle& value, const char* name, std::vector<py::ssize_t> shape, dtype_rule rule = dtype_rule::strict);

/// An (M, 3) float32 array's rows as points.
inline std::span<const glm::vec3> as_points(const float_array& a) {
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    return {reinterpret_cast<const glm::vec3*>(a.data()), std::size_t(a.shape(0))};
}

/// A 3-vector given as a sequence or array of three numbers.
inline glm::vec3 vec3_of(const py::handle& v, const char* name) {
    const auto a = float32_array(v, name, {3}, dtype_rule::convert);
    return {a.at(0), a.at(1), a.at(2)};
}

/// A light given as a spec string ("dir:0,-1,-1") or a Light.
hairshadow::light_spec light_of(const py::handle& light);
/// A light's spec string, which parse_light_spec reads back to the same floats.
std::string light_text(const hairshadow::light_spec& light);

/// The module's headless GL context (`kind` "egl" or "osmesa"; "": the one open, else EGL), opened
/// with GL loaded at the first use and kept for the process's life (GL objects made on it may outlive
/// any Python object), made current. Every use must come from the thread that opened it: a GL context
/// is current on one thread. Throws hairshadow::gl::gl_error where it cannot open or is used from
/// another thread, argument_error for another kind than the one open. Frees the GL objects that other
/// threads retired.
hairshadow::gl::headless_context& gl_context(const std::string& kind);
/// The kind of the open context ("" before any).
std::string gl_context_kind();
/// Keeps GL objects dropped on another thread until gl_context() runs on GL's own thread.
void retire_gl_objects(std::unique_ptr<hairshadow::gl::any_gl_shadow_map> maps, std::unique_ptr<hairshadow::gl::hair_mesh> mesh);

/// Marks a model as read by a call that runs without the GIL (a build, compare, render, bench), so
/// that assigning its arrays meanwhile raises instead of changing what the call reads.
class model_reading {
public:
    explicit model_reading(const hairshadow::hair_model& model);
    ~model_reading();
    model_reading(const model_reading&) = delete;
    model_reading& operator=(const model_reading&) = delete;

private:
    const hairshadow::hair_model* model_;
};

void bind_errors(py::module_& m);
void bind_models(py::module_& m);
void bind_lights(py::module_& m);
void bind_maps(py::module_& m);
void bind_measures(py::module_& m);
void bind_motion(py::module_& m);

} // namespace hspy
