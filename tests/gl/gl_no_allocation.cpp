// An engine rebuilds its GL maps and binds their look-ups every frame: once warm, neither allocates.
// Every C++ allocation of this executable is counted (each form of operator new is replaced), which
// is the route of every allocation the library makes (strings, vectors, its objects). The driver's
// own C allocations (Mesa's malloc) are not the library's and are not counted. Its own executable,
// since replacing operator new is a whole-program choice, and never under a sanitizer.
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/procedural/motion.hpp>


#include <atomic>

// The replacements below hand memory from malloc to free: GCC cannot see that every route pairs them.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#include <cstdlib>
#include <new>

namespace {
std::atomic<std::size_t> allocations{0};

void* counted(std::size_t size, std::size_t alignment = 0) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    if (size == 0) size = 1;
    void* p = alignment > alignof(std::max_align_t) ? std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment) : std::malloc(size);
    return p;
}
} // namespace

void* operator new(std::size_t size) {
    if (void* p = counted(size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
    if (void* p = counted(size)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t a) {
    if (void* p = counted(size, std::size_t(a))) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t a) {
    if (void* p = counted(size, std::size_t(a))) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

using namespace hairshadow;

TEMPLATE_TEST_CASE("once warm, a GL frame (rebuild, then bind the look-up) allocates nothing", "[gl][allocation]", deep_opacity_maps<3>,
                   (occupancy_maps<128, 4>), opacity_shadow_maps<16>, density_clustering<4>, fourier_opacity_maps<7>) {
    test::gl_context();
    const auto path = GENERATE(gl::build_path::compute, gl::build_path::raster);
    CAPTURE(gl::to_string(path));
    const auto model = make_procedural({.style = hair_style::curly, .strands = 300, .segments = 24, .seed = 3});
    const auto box = model.bounds().expanded(0.2f);
    const gl::hair_mesh mesh(model);
    gl::maps<TestType> maps;
    maps.set_build_path(path);
    const auto source = maps.lookup_source("key_");
    const auto vs = gl::compile_shader(GL_VERTEX_SHADER, {"#version 430 core\n", source, "in vec3 p;\nvoid main() { gl_Position = vec4(key_transmittance(p)); }\n"},
                                       "engine look-up");
    const auto prog = gl::link_program({&vs}, "engine look-up");
    const auto frame = [&](float t) {
        maps.build(mesh, light_space::fit(orbit_light(light_spec::directional({0.6f, -1, 0.6f}), t, 2.0f), box, 128));
        maps.bind_lookup(prog.get(), 3, "key_", 0.001f);
    };
    for (int i = 0; i < 3; ++i) frame(0.1f * float(i));
    const std::size_t before = allocations.load();
    for (int i = 0; i < 5; ++i) frame(0.1f * float(i) + 0.05f);
    CHECK(allocations.load() - before == 0);
    glFinish();
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("the GL allocation counter counts the library's route", "[allocation]") {
    const std::size_t before = allocations.load();
    static std::string* volatile sink = nullptr;
    sink = new std::string(100, 'x'); // the string, and its characters
    delete sink;
    CHECK(allocations.load() - before == 2);
}
