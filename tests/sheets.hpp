#pragma once
// Parallel sheets of strands at known depths, one strand through the centre of each texel row, so that
// the exact transmittance behind k sheets is (1 - alpha)^k.

#include <hairshadow/hairshadow.hpp>

#include <cmath>

namespace test {

struct sheets_scene {
    hairshadow::hair_model model;
    hairshadow::light_space light;
    std::vector<float> sheet_z;   ///< world z of each sheet, nearest the light first
    std::vector<float> row_y;     ///< world y of the strands (texel row centres)
};

/// `sheets` sheets at z = 0.5, 0.3, 0.1, ... seen by a light travelling along -z at `res`.
inline sheets_scene make_sheets(int sheets, int res) {
    using namespace hairshadow;
    sheets_scene scene;
    // The x extent (2) decides the map's width; the rows span less than that.
    aabb box;
    box.add({-1, -0.5f, 0.5f - 0.2f * float(sheets - 1)});
    box.add({1, 0.5f, 0.5f});
    scene.light = light_space::fit(light_spec::directional({0, 0, -1}), box, res);
    const float texel = scene.light.texel_size(0.5f);
    // Strands at texel row centres; symmetric about y = 0 so the bounds keep their centre.
    const int half_rows = int(0.5f / texel) - 1;
    for (int j = -half_rows; j < half_rows; ++j) scene.row_y.push_back((float(j) + 0.5f) * texel);
    for (int s = 0; s < sheets; ++s) {
        const float z = 0.5f - 0.2f * float(s);
        scene.sheet_z.push_back(z);
        for (float y : scene.row_y) scene.model.add_strand(std::vector<glm::vec3>{{-1, y, z}, {1, y, z}});
    }
    scene.model.default_thickness = texel;
    return scene;
}

/// Rasteriser options with every fragment's alpha `a`.
inline hairshadow::raster_options alpha(float a) {
    hairshadow::raster_options o;
    o.fixed_alpha = a;
    return o;
}

/// The light depth of world z on the sheets' middle row.
inline float depth_at(const sheets_scene& scene, float z) {
    return scene.light.locate(glm::vec3(0.2f, scene.row_y[scene.row_y.size() / 2], z))->depth;
}

} // namespace test
