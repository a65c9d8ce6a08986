// Models in Python: loaded, procedural or from numpy arrays, and their arrays back as views.
#include "bindings.hpp"

#include <hairshadow/io/load.hpp>

#include <cstdint>
#include <cstring>
#include <mutex>
#include <unordered_map>
#include <optional>

namespace hspy {

using namespace hairshadow;

namespace {

/// A read-only view of `count` x `width` floats at `data`, kept alive by the model `owner`: the
/// model's own memory, no copy. Read-only since a model is checked when made and when an array is set.
py::array float_view(const float* data, std::size_t count, py::ssize_t width, const py::object& owner) {
    std::vector<py::ssize_t> shape{py::ssize_t(count)}, strides{py::ssize_t(sizeof(float)) * width};
    if (width > 1) shape.push_back(width), strides.push_back(sizeof(float));
    py::array view(py::dtype::of<float>(), shape, strides, data, owner);
    view.attr("setflags")(py::arg("write") = false);
    return view;
}

std::vector<std::uint32_t> offsets_of(const py::object& lengths, const py::object& offsets, std::size_t points) {
    if (lengths.is_none() == offsets.is_none()) throw py::value_error("give the strands as strand_lengths or as strand_offsets (one of the two)");
    const auto integers = [](const py::object& o, const char* name) {
        const py::array a = py::array::ensure(o);
        if (!a || a.ndim() != 1 || (a.dtype().kind() != 'i' && a.dtype().kind() != 'u'))
            throw py::type_error(std::string(name) + " must be a 1-D integer array");
        return py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    };
    std::vector<std::uint32_t> out{0};
    if (!lengths.is_none()) {
        const auto l = integers(lengths, "strand_lengths");
        std::uint64_t sum = 0;
        for (py::ssize_t i = 0; i < l.shape(0); ++i) {
            if (l.at(i) < 0) throw py::value_error("strand_lengths[" + std::to_string(i) + "] is negative");
            sum += std::uint64_t(l.at(i));
            if (sum > points) throw py::value_error("strand_lengths add up to more than the " + std::to_string(points) + " points");
            out.push_back(std::uint32_t(sum));
        }
    } else {
        const auto o = integers(offsets, "strand_offsets");
        out.clear();
        for (py::ssize_t i = 0; i < o.shape(0); ++i) {
            if (o.at(i) < 0 || std::uint64_t(o.at(i)) > points)
                throw py::value_error("strand_offsets[" + std::to_string(i) + "] is outside 0.." + std::to_string(points));
            out.push_back(std::uint32_t(o.at(i)));
        }
    }
    return out; // validate() checks the rest: a start at 0, the end at the point count, order
}

template <class T>
std::vector<T> per_point(const py::object& values, const char* name, std::size_t points, py::ssize_t width) {
    if (values.is_none()) return {};
    const auto a = float32_array(values, name, width == 1 ? std::vector<py::ssize_t>{py::ssize_t(points)} : std::vector<py::ssize_t>{py::ssize_t(points), width});
    std::vector<T> out(points);
    std::memcpy(out.data(), a.data(), points * sizeof(T));
    return out;
}

hair_model model_from_arrays(const py::object& points, const py::object& lengths, const py::object& offsets, const py::object& thickness,
                             const py::object& transparency, const py::object& colors) {
    const auto p = float32_array(points, "points", {-1, 3});
    hair_model model;
    model.points.assign(as_points(p).begin(), as_points(p).end());
    model.strand_offsets = offsets_of(lengths, offsets, model.points.size());
    model.thickness = per_point<float>(thickness, "thickness", model.points.size(), 1);
    model.transparency = per_point<float>(transparency, "transparency", model.points.size(), 1);
    model.colors = per_point<glm::vec3>(colors, "colors", model.points.size(), 3);
    validate(model);
    ensure_thickness(model);
    return model;
}

/// Models read by calls running without the GIL, and how many calls read each.
struct readers {
    std::mutex mutex;
    std::unordered_map<const hair_model*, int> count;
};
readers& model_readers() {
    static auto* r = new readers; // never destroyed: a model may be read until the interpreter's end
    return *r;
}

void refuse_while_read(const hair_model& model) {
    auto& r = model_readers();
    std::lock_guard lock(r.mutex);
    if (r.count.contains(&model)) throw py::value_error("the model is being read by a call in another thread (a build, compare, render or bench): assign its arrays after it");
}

/// Sets a per-point array of the model from `values`, checked, keeping the model's own buffer where
/// it has one, so that views of it stay valid and see the new values; a failure leaves the model as
/// it was. An array cannot be removed (views of it would dangle): make a new Model instead.
template <class T>
void set_per_point(hair_model& model, std::vector<T> hair_model::*member, const py::object& values, const char* name, py::ssize_t width) {
    refuse_while_read(model);
    auto& field = model.*member;
    if (values.is_none()) {
        if (field.empty()) return;
        throw py::value_error(std::string(name) + " cannot be removed from a model (views of it may be held): make a new Model without it");
    }
    auto candidate = per_point<T>(values, name, model.points.size(), width); // may throw: the model is untouched
    std::swap(field, candidate);                                             // `candidate` holds the old buffer now
    try {
        validate(model);
    } catch (...) {
        std::swap(field, candidate);
        throw;
    }
    if (!candidate.empty()) { // write the values into the old buffer, which views may hold
        std::copy(field.begin(), field.end(), candidate.begin());
        std::swap(field, candidate);
    }
}

std::string procedural_text(const std::string& spec) { return is_procedural_spec(spec) ? spec : "procedural:" + spec; }

} // namespace

model_reading::model_reading(const hair_model& model) : model_(&model) {
    auto& r = model_readers();
    std::lock_guard lock(r.mutex);
    ++r.count[model_];
}

model_reading::~model_reading() {
    auto& r = model_readers();
    std::lock_guard lock(r.mutex);
    if (--r.count[model_] == 0) r.count.erase(model_);
}

void bind_models(py::module_& m) {
    py::class_<hair_model> model(m, "Model", "A hair model: strands of points, with optional per-point thickness, transparency and colour.");
    model.def(py::init(&model_from_arrays), py::arg("points"), py::kw_only(), py::arg("strand_lengths") = py::none(),
              py::arg("strand_offsets") = py::none(), py::arg("thickness") = py::none(), py::arg("transparency") = py::none(),
              py::arg("colors") = py::none(),
              "A model from numpy arrays (copied once into the model): points (N, 3) float32; the strands as strand_lengths (S,) or "
              "strand_offsets (S + 1,) integers; optional thickness (N,), transparency (N,, 0 opaque .. 1 invisible) and colors (N, 3) "
              "float32. Checked as a loaded model is (ValueError).");
    model.def_property(
        "points", [](py::object self) { const auto& h = self.cast<const hair_model&>(); return float_view(reinterpret_cast<const float*>(h.points.data()), h.points.size(), 3, self); },
        [](hair_model& h, const py::object& values) { set_per_point(h, &hair_model::points, values, "points", 3); },
        "(N, 3) float32, a read-only view of the model's own memory; assign an array of the same shape to move the points (checked, then written into the same memory).");
    model.def_property_readonly(
        "strand_offsets",
        [](py::object self) {
            const auto& h = self.cast<const hair_model&>();
            py::array view(py::dtype::of<std::uint32_t>(), {py::ssize_t(h.strand_offsets.size())}, {py::ssize_t(sizeof(std::uint32_t))},
                           h.strand_offsets.data(), self);
            view.attr("setflags")(py::arg("write") = false);
            return view;
        },
        "(S + 1,) uint32: strand s is points[strand_offsets[s]:strand_offsets[s + 1]] (a view)");
    const auto optional_view = [](auto member, py::ssize_t width) {
        return [member, width](py::object self) -> py::object {
            const auto& v = self.cast<const hair_model&>().*member;
            if (v.empty()) return py::none();
            return float_view(reinterpret_cast<const float*>(v.data()), v.size(), width, self);
        };
    };
    model.def_property("thickness", optional_view(&hair_model::thickness, 1),
                       [](hair_model& h, const py::object& v) { set_per_point(h, &hair_model::thickness, v, "thickness", 1); },
                       "(N,) float32 strand diameter per point (a view), or None for the default_thickness; assignable (checked, written into the same memory)");
    model.def_property("transparency", optional_view(&hair_model::transparency, 1),
                       [](hair_model& h, const py::object& v) { set_per_point(h, &hair_model::transparency, v, "transparency", 1); },
                       "(N,) float32 per point, 0 opaque .. 1 invisible (a view), or None for the default");
    model.def_property("colors", optional_view(&hair_model::colors, 3),
                       [](hair_model& h, const py::object& v) { set_per_point(h, &hair_model::colors, v, "colors", 3); },
                       "(N, 3) float32 linear RGB per point (a view), or None for the default colour");
    model.def_readonly("default_thickness", &hair_model::default_thickness);
    model.def_property_readonly("point_count", &hair_model::point_count);
    model.def_property_readonly("strand_count", &hair_model::strand_count);
    model.def_property_readonly("segment_count", &hair_model::segment_count);
    model.def_property_readonly("bounds", [](const hair_model& h) {
        const auto b = h.bounds();
        return py::make_tuple(py::make_tuple(b.min.x, b.min.y, b.min.z), py::make_tuple(b.max.x, b.max.y, b.max.z));
    }, "((min x, y, z), (max x, y, z))");
    model.def("copy", [](const hair_model& h) { return hair_model(h); }, "A copy with its own arrays.");
    model.def("__repr__", [](const hair_model& h) {
        return "<hairshadow.Model " + std::to_string(h.strand_count()) + " strands, " + std::to_string(h.point_count()) + " points>";
    });

    m.def("load", [](const std::string& path) { py::gil_scoped_release unlocked; return load_model(path); }, py::arg("path"),
          "Reads a .hair, .tfx, .data or .obj hair model, or a procedural spec (procedural:NAME[:key=value...]).");
    m.def("procedural", [](const std::string& spec) { return load_model(procedural_text(spec)); }, py::arg("spec"),
          ("A procedural model: " + std::string(procedural_grammar) + " (the 'procedural:' may be left out).").c_str());
    m.def("save", [](const hair_model& hair, const std::string& path) {
        const model_reading reading(hair);
        py::gil_scoped_release unlocked;
        save_model(hair, path);
    },
          py::arg("model"), py::arg("path"), "Writes a model by extension: .hair, .data or .tfx.");
}

} // namespace hspy
