// The projected methods on GL (projected_maps_gl: Fourier opacity maps, moment shadow maps): the compute path's sums against
// the CPU's tiled build, every texel (the compute comparison's, within 1e-5 of each texel's largest
// sum); the raster path against the CPU run on GL's own fragments; the GLSL look-up against the CPU
// query, with the reconstruction's parameters reaching both; and behind sheets of strands.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/passes/fragment_capture.hpp>

#include "../sheets.hpp"
#include "../test_support.hpp"
#include "compute_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

using namespace hairshadow;

namespace {

/// The GLSL look-up against the CPU query on the maps read back (the same bytes) within 1e-4, and
/// against the CPU's own maps within `against_cpu` (where those differ a little: a level of an 8-bit
/// step, a reconstruction that amplifies the sums' rounding).
template <class GlMaps, class Method>
void check_lookup_on_read_back(GlMaps& on_gl, const Method& cpu, const std::vector<glm::vec3>& queries, float against_cpu) {
    const auto on_gpu = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, queries);
    std::vector<float> on_cpu(queries.size()), from_back(queries.size());
    cpu.transmittance(queries, on_cpu);
    on_gl.to_cpu().transmittance(queries, from_back);
    float worst = 0, worst_same_maps = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
        worst = std::max(worst, std::abs(on_gpu[i] - on_cpu[i]));
        worst_same_maps = std::max(worst_same_maps, std::abs(on_gpu[i] - from_back[i]));
    }
    CAPTURE(worst, worst_same_maps, queries.size());
    CHECK(queries.size() >= 2000);
    CHECK(worst_same_maps < 1e-4f);
    CHECK(worst < against_cpu);
}

/// How far an 8-bit step's level may move a look-up: two steps of kappa / 255 in a coefficient.
constexpr float level_tolerance = 0.05f;

template <class Method>
void check_projected_compute_path(const Method& parameters, const hair_model& model, const light_space& light, const gl::hair_mesh& mesh,
                        const fragment_buffer& fragments) {
    Method cpu = parameters;
    cpu.build(model, light);
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light);
    gl::maps<Method> on_gl(parameters);
    on_gl.build(pass);
    const auto c = test::compare_maps(cpu, on_gl, gl::detail::read_range(*pass.textures()), test::cpu_occupancy(model, light), light.resolution());
    CAPTURE(c.occupied, c.occupancy_off, c.state_off, c.data_off, c.worst, c.levels_off);
    CHECK(c.occupied > 1000);
    CHECK(c.exact());
    // 8-bit steps of terms whose cosines GL and the C library round apart: now and then a level off
    // (1 sum of 121,478 in Sintel's 7-coefficient maps on llvmpipe); at most 1 in 10,000 sums.
    CHECK(c.levels_off * 10000 <= c.occupied * Method::reconstruction_type::sums);
    const auto queries = test::texel_centre_queries(fragments, light, 5);
    if (c.levels_off == 0) test::check_lookup_and_read_back(on_gl, cpu, queries, 0.1f);
    else check_lookup_on_read_back(on_gl, cpu, queries, level_tolerance);
}

} // namespace

TEST_CASE("GL Fourier opacity maps equal the CPU maps, and the GLSL look-up the CPU query", "[gl][fom]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = rasterize(model, light);
    SECTION("7 coefficients, undamped") { check_projected_compute_path(fourier_opacity_maps<7>(), model, light, mesh, fragments); }
    SECTION("7 coefficients in 8 bits: the encoded terms' steps") { check_projected_compute_path(fourier_opacity_maps<7, emulated_8bit>(), model, light, mesh, fragments); }
    SECTION("15 coefficients, damped: more sums than one walk holds at 32 KiB") {
        const fourier_opacity_maps<15> damped{depth_range<1>(), fourier_series<15>(true)};
        check_projected_compute_path(damped, model, light, mesh, fragments);
        gl::maps<fourier_opacity_maps<15>> on_gl(damped);
        on_gl.build(mesh, light);
        CHECK(on_gl.to_cpu().reconstruction().damped());
    }
}

/// The raster path's sums against the CPU's from GL's own fragments (the blending order is GL's), and
/// the look-up against the CPU query. 8-bit steps may lie a level apart now and then (GL's cosines and
/// its conversion to unorm8 round apart from the CPU's); a reconstruction that amplifies the sums'
/// rounding (8 moments) gives `amplified`, the look-up's bound against the CPU's maps. Against the maps
/// read back (the same bytes) the look-up holds within 1e-4 either way.
template <class Method>
void check_raster_path(const Method& parameters, const light_space& light, const gl::hair_mesh& mesh, float amplified = 0.0f) {
    const auto fragments = gl::capture_fragments(mesh, light, raster_options{});
    Method cpu = parameters;
    cpu.build(fragments, light);
    gl::maps<Method> on_gl(parameters);
    on_gl.set_build_path(gl::build_path::raster);
    on_gl.build(mesh, light);
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long state_off = 0, data_off = 0, levels_off = 0, sums = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            state_off += !(c.placement == g.placement); // MIN / MAX blending: bit-exact
            double scale = 1e-3;
            for (const auto v : c.data.sums) scale = std::max(scale, std::abs(double(v)));
            for (std::size_t k = 0; k < c.data.sums.size(); ++k, ++sums) {
                const double off = std::abs(double(c.data.sums[k]) - double(g.data.sums[k]));
                if constexpr (std::is_floating_point_v<std::remove_cvref_t<decltype(c.data.sums[k])>>) {
                    data_off += off > 1e-5 * scale;
                } else {
                    levels_off += off == 1.0;
                    data_off += off > 1.0;
                }
            }
        }
    CAPTURE(levels_off, sums);
    CHECK(state_off == 0);
    CHECK(data_off == 0);
    CHECK(levels_off * 10000 <= sums);
    const auto queries = test::texel_centre_queries(fragments, light, 5);
    if (amplified == 0.0f && levels_off == 0) test::check_lookup_and_read_back(on_gl, cpu, queries, 0.1f);
    else check_lookup_on_read_back(on_gl, cpu, queries, amplified > 0.0f ? amplified : level_tolerance);
}

TEST_CASE("GL's raster path blends the projected sums as the CPU sums them from GL's fragments", "[gl][fom][msm]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    SECTION("fom:7, two targets") { check_raster_path(fourier_opacity_maps<7>(), light, mesh); }
    SECTION("fom:7:8bit, two RGBA8 targets") { check_raster_path(fourier_opacity_maps<7, emulated_8bit>(), light, mesh); }
    SECTION("fom:15 damped, four targets") { check_raster_path(fourier_opacity_maps<15>{depth_range<1>(), fourier_series<15>(true)}, light, mesh); }
    SECTION("msm, two targets") { check_raster_path(moment_shadow_maps<4>{depth_range<1>(), power_moments<4>({.overestimation = 0.6f})}, light, mesh); }
    // Eight moments turn the blend's rounding of the sums (within 1e-5) into up to 5.5e-4 of
    // transmittance on llvmpipe.
    SECTION("msm:8, three targets") {
        check_raster_path(moment_shadow_maps<8>{depth_range<1>(), power_moments<8>({.overestimation = 0.6f})}, light, mesh, 2e-3f);
    }
}

TEST_CASE("the GL look-up gives the Fourier series' transmittance behind sheets of strands", "[gl][fom]") {
    test::gl_context();
    const auto scene = test::make_sheets(5, 64);
    const gl::hair_mesh mesh(scene.model);
    raster_options options;
    options.fixed_alpha = 0.3f;
    for (const bool damped : {false, true}) {
        const fourier_opacity_maps<7> parameters{depth_range<1>(), fourier_series<7>(damped)};
        auto cpu = parameters;
        cpu.build(scene.model, scene.light, options);
        gl::maps<fourier_opacity_maps<7>> on_gl(parameters);
        on_gl.build(mesh, scene.light, options);
        const float y = scene.row_y[scene.row_y.size() / 2];
        std::vector<glm::vec3> points;
        for (const float z : {0.9f, 0.5f, 0.4999f, 0.4f, 0.3f, 0.2f, 0.1f, -0.05f, -0.2f, -0.3f, -0.9f}) points.push_back({0.2f, y, z});
        points.push_back({0.2f, 0.49f, -0.5f}); // a texel with no hair
        const auto t = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, points);
        for (std::size_t i = 0; i < points.size(); ++i) {
            CAPTURE(damped, i, t[i]);
            CHECK(t[i] == Approx(cpu.transmittance(points[i])).epsilon(1e-5));
        }
        CHECK(t.front() == 1.0f);
        CHECK(t[t.size() - 2] == Approx(std::pow(0.7f, 5.0f)).epsilon(1e-5));
        CHECK(t.back() == 1.0f);
    }
}

TEST_CASE("GL moment shadow maps equal the CPU maps, and the GLSL look-up the CPU query", "[gl][msm]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = rasterize(model, light);
    // The upper bound (overestimation 1): a look-up that lost its uniform would read 0 and differ.
    SECTION("4 moments") {
        const moment_shadow_maps<4> upper{depth_range<1>(), power_moments<4>({.overestimation = 1.0f})};
        check_projected_compute_path(upper, model, light, mesh, fragments);
        gl::maps<moment_shadow_maps<4>> on_gl(upper);
        on_gl.build(mesh, light);
        CHECK(on_gl.to_cpu().reconstruction().parameters() == upper.reconstruction().parameters());
    }
    // The cubic's and the quartic's roots by bisection, and a bias of the user's own.
    SECTION("6 moments") { check_projected_compute_path(moment_shadow_maps<6>{depth_range<1>(), power_moments<6>({.overestimation = 1.0f})}, model, light, mesh, fragments); }
    SECTION("8 moments") {
        check_projected_compute_path(moment_shadow_maps<8>{depth_range<1>(), power_moments<8>({.overestimation = 0.0f, .bias = 2e-5f})}, model, light, mesh, fragments);
    }
}

TEST_CASE("the GL look-up gives the moments' transmittance between sheets of strands", "[gl][msm]") {
    test::gl_context();
    const auto check = []<int M>(std::integral_constant<int, M>) {
        // M / 2 sheets, which M moments determine: between them the sheets' shadow, as on the CPU.
        const auto scene = test::make_sheets(M / 2, 64);
        const gl::hair_mesh sheets(scene.model);
        raster_options options;
        options.fixed_alpha = 0.3f;
        gl::maps<moment_shadow_maps<M>> sheets_gl;
        sheets_gl.build(sheets, scene.light, options);
        const float y = scene.row_y[scene.row_y.size() / 2];
        std::vector<glm::vec3> points{{0.2f, y, 0.9f}};
        for (std::size_t s = 0; s + 1 < scene.sheet_z.size(); ++s) points.push_back({0.2f, y, 0.5f * (scene.sheet_z[s] + scene.sheet_z[s + 1])});
        points.push_back({0.2f, y, -0.9f});
        const auto t = test::gl_lookup(sheets_gl.lookup_source(), [&](GLuint p) { sheets_gl.bind_lookup(p); }, points);
        CHECK(t[0] == 1.0f);
        for (std::size_t i = 1; i < points.size(); ++i) {
            CAPTURE(M, i);
            CHECK(t[i] == Approx(std::pow(0.7, double(i))).epsilon(i + 1 < points.size() ? 1e-3 : 1e-5));
        }
    };
    check(std::integral_constant<int, 4>{});
    check(std::integral_constant<int, 6>{});
    check(std::integral_constant<int, 8>{});
}
