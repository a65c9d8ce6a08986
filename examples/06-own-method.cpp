// 06-own-method: a method of your own, outside the library. A placement written here, doubling_slices
// (the slices of occupancy maps' depth range, Sintorn & Assarsson 2009, but each twice as deep as the
// one before: finer where the hair begins), composed with the library's float accumulation and
// interpolation (Kim & Neumann 2001), built on the CPU and, from its GLSL file beside this one
// (06-own-method.glsl), on GL's compute path, with no edit to include/ or shaders/. Prints how far
// the GL maps and the GLSL look-up lie from the CPU's, and exits 1 if they are not the same answers.
//
//   06-own-method [SHADER.glsl]      (default: the 06-own-method.glsl this example was built beside)
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/egl_context.hpp>
#include <hairshadow/hairshadow.hpp>

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <span>
#include <sstream>
#include <string>

namespace {

std::string shader_path = HAIRSHADOW_EXAMPLE_SHADER; // the GLSL file beside this one

/// S slices between each texel's nearest and furthest fragment, slice k of relative depth 2^k / (2^S - 1).
template <int S>
class doubling_slices {
public:
    // What every placement gives (docs/policies.md, "Placement").
    static constexpr int layer_count = S;
    static constexpr bool cumulative = true;  ///< each layer holds the optical depth in front of its end
    static constexpr bool contiguous = true;  ///< the slices tile the range without gaps
    static constexpr std::string_view glsl_name = "example/doubling_slices";
    struct texel_state {
        float nearest = 0.0f, furthest = 0.0f;
        friend bool operator==(const texel_state&, const texel_state&) = default;
    };
    void prepare(const hairshadow::depth_extent&) const noexcept {}
    template <class Fragment>
    void prepare_texel(std::span<const Fragment> fragments, texel_state& s) const noexcept {
        if (fragments.empty()) return;
        float nearest = fragments[0].depth, furthest = nearest;
        for (const auto& f : fragments) nearest = std::min(nearest, f.depth), furthest = std::max(furthest, f.depth);
        texel_state_from(nearest, furthest, s);
    }
    int assign(const texel_state& s, float depth) const noexcept {
        if (!(s.furthest > s.nearest)) return 0;
        return std::clamp(slice_of(s, depth), 0, S - 1);
    }
    hairshadow::layer_position locate(const texel_state& s, float depth) const noexcept {
        if (!(s.furthest > s.nearest)) return {depth > s.nearest ? S : -1, 0.0f};
        if (!(depth >= s.nearest)) return {-1, 0.0f};
        const int k = slice_of(s, depth);
        if (k >= S) return {S, 0.0f};
        const float lo = boundary(s, k), hi = boundary(s, k + 1);
        return {k, hi > lo ? std::clamp((depth - lo) / (hi - lo), 0.0f, 1.0f) : 0.0f};
    }

    // Optional: the state from a texel's nearest and furthest fragment lets the tiled build stream
    // dense tiles without grouping them; a state that depends on the fragments as a set lets it walk
    // them in any order (docs/policies.md, "Capabilities").
    void texel_state_from(float nearest, float furthest, texel_state& s) const noexcept { s = {nearest, furthest}; }
    static constexpr bool fragment_order_free = true;

    // The GL side (gl/maps/policy_glsl.hpp): the GLSL text, and the boundary fractions written for it.
    static std::string glsl_source() {
        std::ifstream in(shader_path);
        if (!in) throw hairshadow::io_error(shader_path, "cannot read the placement's GLSL");
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    static std::string glsl_defines() {
        std::string list;
        char number[32];
        for (const float f : fractions) {
            std::snprintf(number, sizeof number, "%.9g", double(f)); // nine digits: the same float back
            list += (list.empty() ? "" : ", ") + std::string(number) + (std::string(number).find_first_of(".e") == std::string::npos ? ".0" : "");
        }
        return "#define HS_FRACTIONS float[](" + list + ")\n";
    }

private:
    /// (2^k - 1) / (2^S - 1) for k in [0, S], rounded once to float.
    static constexpr std::array<float, S + 1> fractions = [] {
        std::array<float, S + 1> f{};
        for (int k = 0; k <= S; ++k) f[std::size_t(k)] = float(double((1u << k) - 1u) / double((1u << S) - 1u));
        return f;
    }();
    float boundary(const texel_state& s, int k) const noexcept {
        const float offset = (s.furthest - s.nearest) * fractions[std::size_t(k)];
        return s.nearest + offset; // two roundings, as the GLSL's precise expression
    }
    /// The k with boundary(k) <= depth < boundary(k + 1), S past the last: an estimate settled against
    /// the boundaries, so that the layer depends on them alone.
    int slice_of(const texel_state& s, float depth) const noexcept {
        const float rel = (depth - s.nearest) / (s.furthest - s.nearest);
        const float estimate = std::log2(1.0f + rel * float((1u << S) - 1u));
        int k = estimate > 0.0f ? int(std::min(estimate, float(S))) : 0;
        while (k > 0 && depth < boundary(s, k)) --k;
        while (k < S && depth >= boundary(s, k + 1)) ++k;
        return k;
    }
};

using own_method = hairshadow::shadow_method<doubling_slices<16>, hairshadow::float_accumulation, hairshadow::interpolation>;

} // namespace

int main(int argc, char** argv) try {
    using namespace hairshadow;
    if (argc > 1) shader_path = argv[1];
    const hair_model model = make_procedural({.style = hair_style::curly, .strands = 1500, .segments = 24});
    const auto light = light_space::fit(light_spec::directional({-0.4f, -1.0f, 0.3f}), model.bounds(), 256);

    own_method cpu;
    cpu.build(model, light); // the tiled build, streamed, as for the library's placements
    // Queries at texel centres, a quarter, half and three quarters into each covered texel's depth range
    // and just behind it (points on the hair itself sit on fragments' depths, where a look-up's depth
    // and the CPU's may fall on either side).
    std::vector<glm::vec3> points;
    const glm::mat4 to_world = glm::inverse(light.view_projection());
    for (int y = 1; y < light.resolution(); y += 3)
        for (int x = 1; x < light.resolution(); x += 3) {
            const auto& state = cpu.texel(x, y).placement;
            if (!(state.furthest > state.nearest)) continue;
            for (const float f : {0.25f, 0.5f, 0.75f, 1.01f}) {
                const float depth = state.nearest + f * (state.furthest - state.nearest);
                const float res = float(light.resolution());
                const glm::vec4 w = to_world * glm::vec4((float(x) + 0.5f) / res * 2.0f - 1.0f, (float(y) + 0.5f) / res * 2.0f - 1.0f, 2.0f * depth - 1.0f, 1.0f);
                points.push_back(glm::vec3(w) / w.w);
            }
        }
    std::vector<float> on_cpu(points.size());
    cpu.transmittance(points, on_cpu);

    gl::egl_context context(4, 3);
    if (!gladLoadGL(context.loader())) throw gl::gl_error("cannot load GL");
    std::printf("%s\n", context.description().c_str());
    const gl::hair_mesh mesh(model);
    gl::maps<own_method> on_gl; // interpolated_maps_gl, with the placement's GLSL
    on_gl.build(mesh, light);
    const auto texels = on_gl.read_back();
    std::size_t states_off = 0, layers_off = 0;
    double worst_layer = 0.0;
    for (int y = 0; y < light.resolution(); ++y)
        for (int x = 0; x < light.resolution(); ++x) {
            const auto& a = cpu.texel(x, y);
            const auto& b = texels[std::size_t(y) * std::size_t(light.resolution()) + std::size_t(x)];
            states_off += !(a.placement == b.placement);
            for (std::size_t k = 0; k < a.data.layers.size(); ++k) {
                const double error = std::abs(double(a.data.layers[k]) - double(b.data.layers[k])) / std::max(std::abs(double(a.data.layers[k])), 1e-3);
                worst_layer = std::max(worst_layer, error);
                layers_off += error > 1e-6;
            }
        }
    const gl::point_queries queries(on_gl.lookup_source());
    const auto on_gpu = queries.run(points, [&](GLuint program) { on_gl.bind_lookup(program); });
    double worst_t = 0.0, mean_shadow = 0.0;
    for (std::size_t i = 0; i < on_cpu.size(); ++i) worst_t = std::max(worst_t, double(std::abs(on_gpu[i] - on_cpu[i]))), mean_shadow += 1.0 - on_cpu[i];
    std::printf("doubling_slices<16> on %zu points: mean shadow %.4f; GL against CPU: %zu texel states differ, %zu layer sums beyond 1e-6 "
                "(worst %.2e relative), transmittance within %.2e\n",
                on_cpu.size(), mean_shadow / double(on_cpu.size()), states_off, layers_off, worst_layer, worst_t);
    return states_off == 0 && layers_off == 0 && worst_t < 1e-4 && mean_shadow > 0.0 ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
