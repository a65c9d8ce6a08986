#pragma once
// One OSMesa core 4.5 context for all GL tests of the executable, current and loaded.
#include <glad/gl.h>

#include <hairshadow/gl/context/osmesa_context.hpp>

#include <catch2/catch.hpp>

namespace test {
inline hairshadow::gl::osmesa_context& gl_context() {
    static hairshadow::gl::osmesa_context ctx(4, 5);
    ctx.make_current();
    // Reloaded on every call: a test of another context (EGL) may have loaded glad with its functions.
    REQUIRE(gladLoadGL(ctx.loader()) != 0);
    return ctx;
}
} // namespace test

#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/lookup/point_queries.hpp>
#include <hairshadow/hairshadow.hpp>

#include <glm/matrix.hpp>

#include <functional>
#include <string>
#include <vector>

namespace test {

/// Points well inside their texels: the centres of every `step`-th occupied texel, at depths from just
/// in front of its nearest fragment to just behind its furthest.
inline std::vector<glm::vec3> texel_centre_queries(const hairshadow::fragment_buffer& fragments, const hairshadow::light_space& light, int step) {
    std::vector<glm::vec3> queries;
    const glm::mat4 to_world = glm::inverse(light.view_projection());
    const int res = light.resolution();
    for (int y = 1; y < res; y += step)
        for (int x = 1; x < res; x += step) {
            const auto frags = fragments.texel(x, y);
            if (frags.empty()) continue;
            float lo = frags[0].depth, hi = lo;
            for (const auto& f : frags) lo = std::min(lo, f.depth), hi = std::max(hi, f.depth);
            for (float f : {-0.001f, 0.25f, 0.5f, 0.75f, 1.001f}) {
                const float depth = lo + f * (hi - lo);
                const glm::vec4 ndc((float(x) + 0.5f) / float(res) * 2.0f - 1.0f, (float(y) + 0.5f) / float(res) * 2.0f - 1.0f, 2.0f * depth - 1.0f, 1.0f);
                const glm::vec4 w = to_world * ndc;
                queries.push_back(glm::vec3(w) / w.w);
            }
        }
    return queries;
}

/// Runs hs_transmittance(point) in a vertex shader over `points`; `bind` sets the maps' uniforms.
inline std::vector<float> gl_lookup(const std::string& lookup_source, const std::function<void(GLuint)>& bind, const std::vector<glm::vec3>& points) {
    return hairshadow::gl::point_queries(lookup_source).run(points, bind);
}

} // namespace test
