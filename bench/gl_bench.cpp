// Map build time on GL under OSMesa (llvmpipe) beside the CPU kernels, in one run: for each method,
// GL's two build paths (compute shaders, and the papers' raster passes; glFinish included), the CPU's
// tiled build straight from the model, and the CPU's older path (a reused rasterizer's fragment
// buffer, then the build), on the Sintel model at 512x512.
// Run: build/bench/hairshadow_gl_bench
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/osmesa_context.hpp>
#include <hairshadow/hairshadow.hpp>

#include <benchmark/benchmark.h>

#include <memory>

namespace {

using namespace hairshadow;

struct scene {
    hair_model model;
    light_space light;
    std::unique_ptr<gl::osmesa_context> context;
    std::unique_ptr<gl::hair_mesh> mesh;
};

scene& sintel() {
    static scene s = [] {
        scene out;
        out.model = read_tfx(std::string(HAIRSHADOW_SHARED_DIR) + "/data/sintel/sintel_hair.16points.tfx");
        out.light = light_space::fit(light_spec::directional({0, -1, -1}), out.model.bounds(), 512);
        out.context = std::make_unique<gl::osmesa_context>(4, 5);
        if (!gladLoadGL(out.context->loader())) throw gl::gl_error("cannot load GL");
        out.mesh = std::make_unique<gl::hair_mesh>(out.model);
        return out;
    }();
    return s;
}

template <class GLMaps, gl::build_path Path>
void gl_build(benchmark::State& state) {
    auto& s = sintel();
    GLMaps maps;
    maps.set_build_path(Path);
    maps.build(*s.mesh, s.light);
    glFinish();
    for (auto _ : state) {
        maps.build(*s.mesh, s.light);
        glFinish();
    }
}

template <class Method>
void cpu_build(benchmark::State& state) {
    auto& s = sintel();
    Method method;
    method.build(s.model, s.light);
    for (auto _ : state) method.build(s.model, s.light);
}

template <class Method>
void cpu_buffer_build(benchmark::State& state) {
    auto& s = sintel();
    rasterizer raster;
    Method method;
    method.build(raster(s.model, s.light), s.light);
    for (auto _ : state) method.build(raster(s.model, s.light), s.light);
}

#define HAIRSHADOW_BENCH_PAIR(NAME, METHOD, GLMAPS)                                                                                 \
    BENCHMARK_TEMPLATE(cpu_build, METHOD)->Name("cpu_tiled/" NAME)->Unit(benchmark::kMillisecond)->UseRealTime();               \
    BENCHMARK_TEMPLATE(cpu_buffer_build, METHOD)->Name("cpu_buffer/" NAME)->Unit(benchmark::kMillisecond)->UseRealTime();       \
    BENCHMARK_TEMPLATE(gl_build, GLMAPS, gl::build_path::compute)->Name("gl_compute/" NAME)->Unit(benchmark::kMillisecond)->UseRealTime(); \
    BENCHMARK_TEMPLATE(gl_build, GLMAPS, gl::build_path::raster)->Name("gl_raster/" NAME)->Unit(benchmark::kMillisecond)->UseRealTime();

using osm16 = opacity_shadow_maps<16>;
using osm64 = opacity_shadow_maps<64>;
using dom3 = deep_opacity_maps<3>;
using dom3_8bit = deep_opacity_maps_8bit<3>;
using dc4 = density_clustering<4>;
using occ = occupancy_maps<128, 4>;
using docc = deep_occupancy_maps<128, 4>;
using rosm16 = range_opacity_maps<16>;
HAIRSHADOW_BENCH_PAIR("osm:16", osm16, gl::interpolated_maps_gl<osm16>)
HAIRSHADOW_BENCH_PAIR("osm:64", osm64, gl::interpolated_maps_gl<osm64>)
HAIRSHADOW_BENCH_PAIR("dom:3", dom3, gl::interpolated_maps_gl<dom3>)
HAIRSHADOW_BENCH_PAIR("dom:3:8bit", dom3_8bit, gl::interpolated_maps_gl<dom3_8bit>)
HAIRSHADOW_BENCH_PAIR("dc:4", dc4, gl::interpolated_maps_gl<dc4>)
HAIRSHADOW_BENCH_PAIR("occ:128:4", occ, gl::occupancy_maps_gl<occ>)
HAIRSHADOW_BENCH_PAIR("docc:128:4", docc, gl::occupancy_maps_gl<docc>)
HAIRSHADOW_BENCH_PAIR("rosm:16", rosm16, gl::interpolated_maps_gl<rosm16>)

} // namespace

BENCHMARK_MAIN();
