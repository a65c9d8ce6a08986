// Opacity shadow maps, deep opacity maps (float and 8-bit) and range opacity maps on GL's raster path against the
// CPU kernels, both built from the fragments GL rasterised.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/passes/fragment_capture.hpp>
#include <hairshadow/gl/maps/interpolated_maps.hpp>

#include "../test_support.hpp"

#include <cstring>

using namespace hairshadow;

namespace {

/// The GLSL look-up of `on_gl` against the CPU query of `cpu_maps` at texel-centre points.
template <class GLMaps, class CpuMaps>
void check_lookup(GLMaps& on_gl, const CpuMaps& cpu_maps, const light_space& light, const fragment_buffer& fragments) {
    const auto queries = test::texel_centre_queries(fragments, light, 5);
    const auto on_gpu = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, queries);
    std::vector<float> on_cpu(queries.size());
    cpu_maps.transmittance(queries, on_cpu);
    float worst_t = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) worst_t = std::max(worst_t, std::abs(on_gpu[i] - on_cpu[i]));
    CAPTURE(worst_t, queries.size());
    CHECK(queries.size() >= 1000);
    // Layer sums may differ by 1e-5 relative (summed in another order), which moves T by up to
    // 1e-5 x max(omega e^-omega), a few 1e-6; GLSL's exponential adds its own.
    CHECK(worst_t < 5e-5f);
}

/// A GL layer against the CPU's: the difference in steps (8-bit) or relative (float), and whether it
/// exceeds what the acceptance allows (one step; 1e-5).
template <bool EightBit>
std::pair<float, bool> layer_error(float cpu, float gl) {
    const float error = EightBit ? std::abs(cpu - gl) : std::abs(cpu - gl) / std::max(std::abs(cpu), 1e-3f);
    return {error, EightBit ? error > 1.0f : error > 1e-5f};
}

template <class Method>
void check_interpolated(const light_space& light, const gl::hair_mesh& mesh, const fragment_buffer& fragments) {
    constexpr bool eight_bit = std::is_same_v<typename Method::accumulation_type, emulated_8bit>;
    Method cpu;
    cpu.build(fragments, light);
    gl::interpolated_maps_gl<Method> on_gl;
    on_gl.set_build_path(gl::build_path::raster); // the papers' passes, against the CPU run on GL's own fragments
    on_gl.build(mesh, light, raster_options{});
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long state_off = 0, layers_off = 0, occupied = 0;
    float worst = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            occupied += !fragments.texel(x, y).empty();
            if constexpr (!std::is_empty_v<decltype(c.placement)>) state_off += std::memcmp(&c.placement, &g.placement, sizeof(c.placement)) != 0;
            for (int k = 0; k < Method::layer_count; ++k) {
                const auto [error, off] = layer_error<eight_bit>(float(c.data.layers[std::size_t(k)]), float(g.data.layers[std::size_t(k)]));
                worst = std::max(worst, error);
                layers_off += off;
            }
        }
    CAPTURE(worst);
    CHECK(occupied > 1000);
    CHECK(state_off == 0);  // z0 / depth range: MIN and MAX blending, bit-exact
    CHECK(layers_off == 0); // float sums within 1e-5 relative; 8-bit within one step
    check_lookup(on_gl, cpu, light, fragments);
}

/// Density clustering: its state (means, standard deviations) is summed in float on GL and in double
/// on the CPU, so it is compared within a tolerance; the histograms GL sums from its own state are
/// compared with the CPU's histograms from that same state, and GL's look-up with the CPU's query of
/// GL's maps.
template <class Method>
void check_clustered(const light_space& light, const gl::hair_mesh& mesh, const fragment_buffer& fragments) {
    using P = typename Method::placement_type;
    using A = typename Method::accumulation_type;
    constexpr bool eight_bit = std::is_same_v<A, emulated_8bit>;
    Method cpu;
    cpu.build(fragments, light);
    gl::interpolated_maps_gl<Method> on_gl;
    on_gl.set_build_path(gl::build_path::raster); // the papers' passes, against the CPU run on GL's own fragments
    on_gl.build(mesh, light, raster_options{});
    const auto texels = on_gl.read_back();
    const int res = light.resolution();
    long occupied = 0, state_off = 0, layers_off = 0, cpu_layers_off = 0;
    float worst_state = 0, worst_layer = 0;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const auto in = fragments.texel(x, y);
            if (in.empty()) continue;
            ++occupied;
            const auto& c = cpu.texel(x, y);
            const auto& g = texels[std::size_t(y) * std::size_t(res) + std::size_t(x)];
            float state_error = 0;
            for (std::size_t j = 0; j < std::size_t(P::layer_count); ++j)
                state_error = std::max({state_error, std::abs(c.placement.mean[j] - g.placement.mean[j]),
                                        std::abs(c.placement.sigma[j] - g.placement.sigma[j])});
            worst_state = std::max(worst_state, state_error);
            state_off += state_error > 1e-5f;
            typename Method::texel_maps from_gl_state{g.placement, {}};
            interpolation::build<P, A>(cpu.placement(), g.placement, in, from_gl_state.data);
            for (std::size_t k = 0; k < std::size_t(P::layer_count); ++k) {
                const auto [error, off] = layer_error<eight_bit>(float(from_gl_state.data.layers[k]), float(g.data.layers[k]));
                worst_layer = std::max(worst_layer, error);
                layers_off += off;
                cpu_layers_off += c.data.layers[k] != from_gl_state.data.layers[k];
            }
        }
    CAPTURE(occupied, state_off, worst_state, worst_layer, cpu_layers_off);
    CHECK(occupied > 1000);
    // Means and sigmas within 1e-5 (depth is in [0, 1]) except where float sums moved a fragment
    // across a boundary between clusters; on this model such texels are below 0.5%.
    CHECK(state_off * 200 < occupied);
    CHECK(layers_off == 0);
    check_lookup(on_gl, on_gl.to_cpu(), light, fragments); // GL's maps read back: its own state
}

} // namespace

TEST_CASE("GL interpolated maps equal the CPU maps, and the GLSL look-up the CPU query", "[gl][interpolation]") {
    test::gl_context();
    const auto model = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 256);
    const gl::hair_mesh mesh(model);
    const auto fragments = gl::capture_fragments(mesh, light, raster_options{});
    SECTION("opacity shadow maps 16") { check_interpolated<opacity_shadow_maps<16>>(light, mesh, fragments); }
    SECTION("opacity shadow maps 64, gamma: two passes of 32") { check_interpolated<opacity_shadow_maps<64, gamma_spacing>>(light, mesh, fragments); }
    SECTION("opacity shadow maps 16, 8-bit") { check_interpolated<opacity_shadow_maps<16, uniform_spacing, emulated_8bit>>(light, mesh, fragments); }
    SECTION("deep opacity maps 3") { check_interpolated<deep_opacity_maps<3>>(light, mesh, fragments); }
    SECTION("deep opacity maps 3, 8-bit (hybrid)") { check_interpolated<deep_opacity_maps_8bit<3>>(light, mesh, fragments); }
    SECTION("range opacity maps 16 (hybrid)") { check_interpolated<range_opacity_maps<16>>(light, mesh, fragments); }
    SECTION("density clustering 4") { check_clustered<density_clustering<4>>(light, mesh, fragments); }
    SECTION("density clustering 5: a whole tile's sums and state (30 KiB) in one strip at llvmpipe's 32 KiB") {
        check_clustered<density_clustering<5>>(light, mesh, fragments);
    }
    SECTION("density clustering 6, 8-bit: two state layers") {
        check_clustered<shadow_method<clustered<6>, emulated_8bit, interpolation>>(light, mesh, fragments);
    }
    SECTION("deep opacity maps 4, uniform, extended") {
        check_interpolated<shadow_method<per_pixel_depth<4, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation, interpolation>>(
            light, mesh, fragments);
    }
}

TEST_CASE("GL builds refuse the raster options the CPU refuses: a NaN alpha", "[gl][hostile]") {
    test::gl_context();
    const auto model = test::grid_model(6, 5);
    const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), 32);
    const gl::hair_mesh mesh(model);
    raster_options nan_alpha;
    nan_alpha.fixed_alpha = std::numeric_limits<float>::quiet_NaN();
    gl::maps<deep_opacity_maps<3>> interpolated;
    CHECK_THROWS_AS(interpolated.build(mesh, light, nan_alpha), argument_error);
    gl::maps<occupancy_maps<128, 4>> occupancy;
    CHECK_THROWS_AS(occupancy.build(mesh, light, nan_alpha), argument_error);
    raster_options too_wide;
    too_wide.wide_line_width = 1.0f;
    CHECK_THROWS_AS(interpolated.build(mesh, light, too_wide), argument_error);
}
