#pragma once
// The scene of `render` and `figure`: the hair, its opaque mesh (an OBJ's faces, or a procedural
// model's sphere) and the lights, the first at full strength and the others as fill lights.
#include "progress.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/obj_format.hpp>

#include <string>
#include <vector>

namespace cli {

inline hairshadow::scene load_scene(const std::string& model, const std::string& mesh, const std::vector<hairshadow::light_spec>& lights) {
    using namespace hairshadow;
    scene sc;
    sc.hair = step("loading the model", [&] { return load_model(model); });
    if (!mesh.empty()) sc.mesh = step("loading the mesh", [&] { return read_obj(mesh).mesh; });
    else if (is_procedural_spec(model)) sc.mesh = make_sphere({0, 0, 0}, parse_procedural_spec(model).head_radius, 64);
    for (std::size_t i = 0; i < lights.size(); ++i) sc.lights.push_back({lights[i], glm::vec3(i == 0 ? 1.1f : 0.45f)});
    return sc;
}

} // namespace cli
