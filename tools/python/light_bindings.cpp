// Lights in Python: made from the command line's spec strings or by type, and a light fitted to a
// model (its projection) for mapping points to texels.
#include "bindings.hpp"

#include <glm/glm.hpp>

#include <cstdio>

namespace hspy {

using namespace hairshadow;

hairshadow::light_spec light_of(const py::handle& light) {
    if (py::isinstance<py::str>(light)) return parse_light_spec(light.cast<std::string>());
    if (py::isinstance<light_spec>(light)) return light.cast<light_spec>();
    throw py::type_error("a light is a spec string (" + std::string(light_grammar) + ") or a hairshadow.Light");
}

std::string light_text(const light_spec& light) {
    char buf[256];
    const auto v = [](const glm::vec3& a, char* out, std::size_t n) { std::snprintf(out, n, "%.9g,%.9g,%.9g", double(a.x), double(a.y), double(a.z)); };
    char a[96], b[96];
    switch (light.type) {
    case light_type::directional: v(light.direction, a, sizeof a); std::snprintf(buf, sizeof buf, "dir:%s", a); break;
    case light_type::point: v(light.position, a, sizeof a); std::snprintf(buf, sizeof buf, "point:%s", a); break;
    case light_type::spot:
        v(light.position, a, sizeof a);
        v(light.direction, b, sizeof b);
        std::snprintf(buf, sizeof buf, "spot:%s:%s:%.9g", a, b, double(light.spot_half_angle_degrees));
        break;
    }
    return buf;
}

namespace {

py::array_t<float> matrix(const glm::mat4& m) { // row-major 4x4 from GLM's columns
    py::array_t<float> out({4, 4});
    auto r = out.mutable_unchecked<2>();
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) r(row, col) = m[col][row];
    return out;
}
} // namespace

void bind_lights(py::module_& m) {
    py::class_<light_spec> light_class(m, "Light", "A light: directional, point or spot, as the command line's --light.");
    light_class.def(py::init([](const std::string& spec) { return parse_light_spec(spec); }), py::arg("spec"),
              ("A light from a spec: " + std::string(light_grammar)).c_str());
    light_class.def_static("directional", [](const py::object& d) { return parse_light_spec(light_text(light_spec::directional(vec3_of(d, "direction")))); }, py::arg("direction"));
    light_class.def_static("point", [](const py::object& p) { return parse_light_spec(light_text(light_spec::point(vec3_of(p, "position")))); }, py::arg("position"));
    light_class.def_static("spot", [](const py::object& p, const py::object& d, float half_angle) {
        const auto s = light_spec::spot(vec3_of(p, "position"), vec3_of(d, "direction"), half_angle);
        return parse_light_spec(light_text(s)); // checked as a spec is
    }, py::arg("position"), py::arg("direction"), py::arg("half_angle_degrees"));
    light_class.def_property_readonly("type", [](const light_spec& l) {
        return l.type == light_type::directional ? "directional" : l.type == light_type::point ? "point" : "spot";
    });
    light_class.def_property_readonly("direction", [](const light_spec& l) { return py::make_tuple(l.direction.x, l.direction.y, l.direction.z); });
    light_class.def_property_readonly("position", [](const light_spec& l) { return py::make_tuple(l.position.x, l.position.y, l.position.z); });
    light_class.def_readonly("half_angle_degrees", &light_spec::spot_half_angle_degrees);
    light_class.def_property_readonly("spec", &light_text, "The spec string, which reads back to the same light.");
    light_class.def("__repr__", [](const light_spec& l) { return "hairshadow.Light('" + light_text(l) + "')"; });

    py::class_<light_space> space(m, "LightSpace", "A light fitted to a model at a resolution: the projection of a shadow map.");
    space.def(py::init([](const py::object& light, const hair_model& hair, int resolution) {
        check_resolution(resolution);
        return light_space::fit(light_of(light), hair.bounds(), resolution);
    }), py::arg("light"), py::arg("model"), py::arg("resolution"));
    space.def_property_readonly("resolution", &light_space::resolution);
    space.def_property_readonly("perspective", &light_space::perspective);
    space.def_property_readonly("view", [](const light_space& s) { return matrix(s.view()); }, "4x4 float32, row-major");
    space.def_property_readonly("projection", [](const light_space& s) { return matrix(s.projection()); }, "4x4 float32, row-major");
    space.def_property_readonly("near", &light_space::near_plane);
    space.def_property_readonly("far", &light_space::far_plane);
    space.def("project", [](const light_space& s, const py::object& points) {
        const auto p = float32_array(points, "points", {-1, 3});
        py::array_t<float> out({p.shape(0), py::ssize_t(4)});
        auto o = out.mutable_unchecked<2>();
        const auto pts = as_points(p);
        for (py::ssize_t i = 0; i < p.shape(0); ++i) {
            const auto q = s.project(pts[std::size_t(i)]);
            o(i, 0) = q.window.x, o(i, 1) = q.window.y, o(i, 2) = q.depth, o(i, 3) = q.w;
        }
        return out;
    }, py::arg("points"), "(M, 4) float32: window x, window y (texel (int(x), int(y))), linear depth 0..1, clip w (> 0 in front)");
    space.def("world_point", [](const light_space& s, float x, float y, float depth) {
        // The inverse of project: window (x, y) and linear depth back to a world point.
        const float distance = s.distance_of_depth(depth);
        const glm::vec2 ndc(2.0f * x / float(s.resolution()) - 1.0f, 2.0f * y / float(s.resolution()) - 1.0f);
        const glm::mat4 inverse = glm::inverse(s.view_projection());
        glm::vec4 near_point = inverse * glm::vec4(ndc, -1.0f, 1.0f), far_point = inverse * glm::vec4(ndc, 1.0f, 1.0f);
        const glm::vec3 a = glm::vec3(near_point) / near_point.w, b = glm::vec3(far_point) / far_point.w;
        const float da = s.distance_of(a), db = s.distance_of(b);
        const glm::vec3 p = a + (b - a) * ((distance - da) / (db - da));
        return py::make_tuple(p.x, p.y, p.z);
    }, py::arg("x"), py::arg("y"), py::arg("depth"), "The world point at window (x, y) and linear depth: a point on the light ray of texel (int(x), int(y)).");
    space.def("__repr__", [](const light_space& s) {
        return "<hairshadow.LightSpace " + std::to_string(s.resolution()) + "x" + std::to_string(s.resolution()) + (s.perspective() ? ", perspective>" : ", orthographic>");
    });
}

} // namespace hspy
