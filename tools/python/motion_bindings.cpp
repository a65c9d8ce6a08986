// Moving hair in Python: the library's wind sway and light orbit, the motions of `hairshadow animate`,
// for measuring a method's flicker with hairshadow.TemporalError.
#include "bindings.hpp"

#include <hairshadow/procedural/motion.hpp>

namespace hspy {

using namespace hairshadow;

void bind_motion(py::module_& m) {
    py::class_<sway_motion>(m, "Sway", "Wind sway of a model at rest: pose(t) is the model at time t (seconds), the same for a seed.")
        .def(py::init([](const hair_model& rest, float amplitude_degrees, float period, std::uint64_t seed, const py::object& wind, const py::object& up) {
            sway_options o;
            o.amplitude_degrees = amplitude_degrees;
            o.period = period;
            o.seed = seed;
            o.wind = vec3_of(wind, "wind");
            o.up = vec3_of(up, "up");
            return sway_motion(rest, o);
        }), py::arg("rest"), py::kw_only(), py::arg("amplitude_degrees") = 14.0f, py::arg("period") = 2.0f, py::arg("seed") = 1u,
            py::arg("wind") = py::make_tuple(1.0f, 0.0f, 0.0f), py::arg("up") = py::make_tuple(0.0f, 1.0f, 0.0f))
        .def("pose", [](const sway_motion& s, float t, unsigned threads) {
            py::gil_scoped_release unlocked;
            return s.pose(t, execution{threads});
        }, py::arg("t"), py::arg("threads") = 0u, "A new Model: the rest model posed at time t.");
    m.def("orbit_light", [](const py::object& light, float t, float period, const py::object& centre) {
        return orbit_light(light_of(light), t, period, vec3_of(centre, "centre"));
    }, py::arg("light"), py::arg("t"), py::arg("period"), py::arg("centre") = py::make_tuple(0.0f, 0.0f, 0.0f),
       "The light turned about the vertical axis through centre by t / period of a full turn (`hairshadow animate`'s light).");
}

} // namespace hspy
