// A renderer rebuilds its maps every frame: once warm, posing the moving hair and rebuilding a method's
// maps from it allocate nothing. Every operator new of this executable is counted (its own
// executable, since replacing the global allocator is a whole-program choice).
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/procedural/motion.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<std::size_t> allocations{0};
}

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete" // these operators pair malloc and free themselves
#endif

void* operator new(std::size_t size) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void* operator new(std::size_t size, std::align_val_t align) {
    allocations.fetch_add(1, std::memory_order_relaxed);
    const std::size_t a = std::size_t(align);
    if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) { return ::operator new(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

using namespace hairshadow;

TEMPLATE_TEST_CASE("once warm, a frame of moving hair allocates nothing", "[motion][allocation]", deep_opacity_maps<3>,
                   (occupancy_maps<128, 4>), opacity_shadow_maps<16>, density_clustering<4>, approximate_deep_shadow_maps) {
    const unsigned threads = GENERATE(1u, 2u);
    const sway_motion sway(make_procedural({.style = hair_style::curly, .strands = 400, .segments = 40, .seed = 2}), {.amplitude_degrees = 30.0f});
    const auto box = sway.rest().bounds().expanded(0.2f);
    raster_options options;
    options.exec.threads = threads;
    hair_model moving;
    TestType maps;
    const auto frame = [&](float t) {
        sway.pose(t, moving, options.exec);
        maps.build(moving, light_space::fit(orbit_light(light_spec::directional({0.6f, -1, 0.6f}), t, 2.0f), box, 256), options);
    };
    // Warm-up: two full swings (and orbits) in steps of 0.1 s, so that the working memory has seen the
    // largest frames; then frames at times between those, none seen before.
    for (int i = 0; i < 40; ++i) frame(0.1f * float(i));
    const std::size_t before = allocations.load();
    for (int i = 0; i < 20; ++i) frame(0.1f * float(i) + 0.05f);
    const std::size_t during = allocations.load() - before;
    CHECK(during == 0);
    CHECK(maps.fragment_count() > 0);
}

TEST_CASE("the allocation counter counts", "[allocation]") {
    const std::size_t before = allocations.load();
    static std::vector<int>* volatile sink = nullptr; // volatile: the compiler may not elide the pair
    sink = new std::vector<int>(100);                  // one for the vector, one for its elements
    delete sink;
    CHECK(allocations.load() - before == 2);
}
