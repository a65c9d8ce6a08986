// Occupancy maps on GL's raster path against the CPU kernel, both built from the fragments GL rasterised.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/passes/fragment_capture.hpp>
#include <hairshadow/gl/maps/occupancy_maps.hpp>
#include <hairshadow/hairshadow.hpp>

#include <glm/matrix.hpp>

#include <cstring>

#include "../test_support.hpp"

using namespace hairshadow;

namespace {

template <class Method>
void check_occupancy(const hair_model& model, const light_space& light) {
    constexpr int B = Method::reconstruction_type::slab_count;
    constexpr bool eight_bit = std::is_same_v<typename Method::accumulation_type, emulated_8bit>;
    test::gl_context();
    const gl::hair_mesh mesh(model);
    const raster_options options;
    const fragment_buffer fragments = gl::capture_fragments(mesh, light, options);
    REQUIRE(fragments.size() > 10000);
    Method cpu;
    cpu.build(fragments, light);
    gl::occupancy_maps_gl<Method> on_gl;
    on_gl.set_build_path(gl::build_path::raster); // the papers' passes, against the CPU run on GL's own fragments
    on_gl.build(mesh, light, options);
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long range_off = 0, bits_off = 0, slabs_off = 0, occupied = 0;
    float worst_slab = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            occupied += !fragments.texel(x, y).empty();
            range_off += std::memcmp(&c.placement, &g.placement, sizeof(c.placement)) != 0;
            bits_off += c.data.bits != g.data.bits;
            for (int s = 0; s < B; ++s) {
                const float a = float(c.data.slabs[std::size_t(s)]), b = float(g.data.slabs[std::size_t(s)]);
                const float error = eight_bit ? std::abs(a - b) : std::abs(a - b) / std::max(std::abs(a), 1e-3f);
                worst_slab = std::max(worst_slab, error);
                slabs_off += eight_bit ? error > 1.0f : error > 1e-5f;
            }
        }
    CAPTURE(worst_slab);
    CHECK(occupied > 1000);
    CHECK(range_off == 0); // MIN / MAX blending: the placement's state is bit-exact
    CHECK(bits_off == 0);  // OR-ed occupancy bits: bit-exact
    CHECK(slabs_off == 0); // additive float sums within 1e-5 relative; 8-bit within one step

    // The GLSL look-up equals the CPU query at points well inside their texels (texel centres, at
    // depths through each texel's hair); at the model's own points it agrees but where a point lies
    // within float rounding of a texel edge, and the two sides may pick neighbouring texels.
    auto queries = test::texel_centre_queries(fragments, light, 5);
    const std::size_t query_count = queries.size();
    queries.insert(queries.end(), model.points.begin(), model.points.end());
    const auto on_gpu = test::gl_lookup(gl::occupancy_maps_gl<Method>::lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, queries);
    std::vector<float> on_cpu(queries.size());
    cpu.transmittance(queries, on_cpu);
    float worst = 0;
    int shadowed = 0;
    for (std::size_t i = 0; i < query_count; ++i) {
        worst = std::max(worst, std::abs(on_gpu[i] - on_cpu[i]));
        shadowed += on_cpu[i] < 0.9f;
    }
    std::size_t model_off = 0;
    for (std::size_t i = query_count; i < queries.size(); ++i) model_off += std::abs(on_gpu[i] - on_cpu[i]) > 1e-5f;
    CAPTURE(worst, query_count, model_off);
    CHECK(query_count >= 1000);
    CHECK(shadowed > 500);
    // A query's slice and its fraction inside it are the CPU's (hs_div_rn), but the reconstruction's
    // own quotients use GLSL's division, good to 2.5 ULP: T may differ by a few 1e-6 to 1e-5.
    CHECK(worst < 5e-5f);
    CHECK(model_off * 200 < model.point_count()); // under 0.5% of the model's points, all at texel edges
}

} // namespace

TEST_CASE("GL occupancy maps equal the CPU maps, and the GLSL look-up the CPU query", "[gl][occ]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    SECTION("occupancy maps 128/4") { check_occupancy<occupancy_maps<128, 4>>(model, light); }
    SECTION("occupancy maps 256/8") { check_occupancy<occupancy_maps<256, 8>>(model, light); }
    SECTION("occupancy maps 32/1, 8-bit") { check_occupancy<occupancy_maps<32, 1, emulated_8bit>>(model, light); }
    SECTION("deep occupancy maps 128/4 (hybrid)") { check_occupancy<deep_occupancy_maps<128, 4>>(model, light); }
}

TEST_CASE("a method needing more draw buffers than the context has names them", "[gl][errors]") {
    test::gl_context();
    GLint draw_buffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
    REQUIRE(draw_buffers < 16);
    // 2048 slices are 16 RGBA32UI occupancy targets; 40 clusters need 10 + 10 state targets.
    using many_slices = gl::occupancy_maps_gl<occupancy_maps<2048, 4>>;
    using many_clusters = gl::interpolated_maps_gl<density_clustering<40>>;
    CHECK_THROWS_AS(many_slices(), gl::feature_error);
    CHECK_THROWS_WITH(many_slices(), Catch::Contains("need 16 draw buffers"));
    CHECK_THROWS_AS(many_clusters(), gl::feature_error);
    CHECK_THROWS_WITH(many_clusters(), Catch::Contains("needs 20 draw buffers"));
}
