// The Python module `hairshadow`: models, lights and every registered method as numpy arrays in and
// out (docs/python.md). The bindings are split by subject: models, lights, maps, measures.
#include <glad/gl.h> // before the GL headers

#include "bindings.hpp"
#include "../command_line.hpp"

#include <hairshadow/gl/context/error.hpp>

#include <cerrno>
#include <filesystem>
#include <new>

namespace hspy {

float_array float32_array(const py::handle& value, const char* name, std::vector<py::ssize_t> shape, dtype_rule rule) {
    const auto expected = [&] {
        std::string s = "(";
        for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + (shape[i] < 0 ? std::string("n") : std::to_string(shape[i]));
        return s + (shape.size() == 1 ? ",)" : ")");
    };
    py::array array;
    if (py::isinstance<py::array_t<float>>(value)) { // float32 by equivalence, not by the dtype object's identity
        array = py::reinterpret_borrow<py::array>(value);
    } else if (py::isinstance<py::array>(value)) {
        array = py::reinterpret_borrow<py::array>(value);
        const char kind = array.dtype().kind();
        if (rule == dtype_rule::strict || (kind != 'f' && kind != 'i' && kind != 'u'))
            throw py::type_error(std::string(name) + " must be a float32 array of shape " + expected() + ", not " +
                                 std::string(py::str(array.dtype())) + " (use .astype(numpy.float32))");
        array = array.attr("astype")("float32");
    } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        array = py::module_::import("numpy").attr("asarray")(value, "float32");
    } else {
        throw py::type_error(std::string(name) + " must be a float32 array of shape " + expected() + ", not " +
                             std::string(py::str(value.get_type().attr("__name__"))));
    }
    bool fits = array.ndim() == py::ssize_t(shape.size());
    for (std::size_t i = 0; fits && i < shape.size(); ++i) fits = shape[i] < 0 || array.shape(py::ssize_t(i)) == shape[i];
    if (!fits) {
        std::string got = "(";
        for (py::ssize_t i = 0; i < array.ndim(); ++i) got += (i ? ", " : "") + std::to_string(array.shape(i));
        throw py::value_error(std::string(name) + " must have shape " + expected() + ", not " + got + (array.ndim() == 1 ? ",)" : ")"));
    }
    return float_array::ensure(array); // a copy only where not C-contiguous
}

void bind_errors(py::module_& m) {
    // The library's typed errors as Python's own, with the same messages: bad arguments, specs and
    // models are ValueError, files OSError (FileNotFoundError where the file is not there), GL's
    // RuntimeError (hairshadow.GLError), anything else of the library's RuntimeError.
    // Never destroyed: the translator may run until the interpreter's end.
    static auto* gl_error = new py::exception<hairshadow::gl::gl_error>(m, "GLError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const hairshadow::io_error& e) {
            // A missing file as Python's own (errno, reason, filename: "[Errno 2] no such file: 'FILE'"),
            // any other file error with the library's message ("FILE: reason").
            std::error_code ec;
            if (!std::filesystem::exists(e.file(), ec) && !ec) {
                const auto error = py::reinterpret_borrow<py::object>(PyExc_FileNotFoundError)(ENOENT, e.reason(), e.file());
                PyErr_SetObject(PyExc_FileNotFoundError, error.ptr());
            } else {
                PyErr_SetString(PyExc_OSError, e.what());
            }
        } catch (const cli::usage_error& e) { // the command's checks of the same options
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const hairshadow::argument_error& e) { // spec_error included
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const hairshadow::model_error& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const hairshadow::gl::gl_error& e) {
            (*gl_error)(e.what());
        } catch (const hairshadow::error& e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        }
    });
}

} // namespace hspy

PYBIND11_MODULE(hairshadow, m) {
    m.doc() = "hairshadow: self-shadowing and transparency of hair - every method as numpy arrays in and out";
    m.attr("__version__") = HAIRSHADOW_PYTHON_VERSION;
    hspy::bind_errors(m);
    hspy::bind_models(m);
    hspy::bind_lights(m);
    hspy::bind_maps(m);
    hspy::bind_measures(m);
    hspy::bind_motion(m);
}
