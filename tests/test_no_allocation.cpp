// A renderer rebuilds its maps every frame: once warm, posing the moving hair and rebuilding a method's
// maps from it allocate nothing. Every allocation of this executable is counted, whatever its route:
// the C allocation functions are replaced (glibc's own are called underneath), so operator new (which
// calls malloc), std::aligned_alloc (the maps' huge-page blocks, core/detail/huge_pages.hpp) and the C
// library's callers all pass through the counter. Its own executable, since replacing the allocator
// is a whole-program choice, and never under a sanitizer, which replaces it itself.
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/core/detail/huge_pages.hpp>
#include <hairshadow/procedural/motion.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <new>

#include <unistd.h>

namespace {
std::atomic<std::size_t> allocations{0};
void count() noexcept { allocations.fetch_add(1, std::memory_order_relaxed); }
} // namespace

// Replacements of the functions that glibc's manual ("Replacing malloc") lists: each counts the call
// and hands it on to glibc's own allocator, which glibc exports as __libc_malloc and its kin.
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t count, std::size_t size) noexcept;
void* __libc_realloc(void* p, std::size_t size) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void __libc_free(void* p) noexcept;

void* malloc(std::size_t size) noexcept {
    count();
    return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
    count();
    return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) noexcept {
    count();
    return __libc_realloc(p, size);
}
void free(void* p) noexcept { __libc_free(p); }
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
    count();
    return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
    count();
    return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
    count();
    if (alignment < sizeof(void*) || (alignment & (alignment - 1)) != 0) return EINVAL;
    void* p = __libc_memalign(alignment, size);
    if (!p) return ENOMEM;
    *out = p;
    return 0;
}
void* valloc(std::size_t size) noexcept {
    count();
    return __libc_memalign(std::size_t(sysconf(_SC_PAGESIZE)), size);
}
void* pvalloc(std::size_t size) noexcept {
    count();
    const std::size_t page = std::size_t(sysconf(_SC_PAGESIZE));
    return __libc_memalign(page, (size + page - 1) / page * page);
}
}

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

TEST_CASE("the allocation counter counts every route", "[allocation]") {
    std::size_t before = allocations.load();
    static std::vector<int>* volatile sink = nullptr; // volatile: the compiler may not elide the pair
    sink = new std::vector<int>(100);                  // one for the vector, one for its elements
    delete sink;
    CHECK(allocations.load() - before == 2);
    // The maps' route: blocks of 2 MiB and more from std::aligned_alloc, smaller ones from operator new.
    before = allocations.load();
    detail::huge_page_allocator<float> maps;
    constexpr std::size_t large = std::size_t(1) << 20, small = 1000; // 4 MiB and 4000 bytes of floats
    float* volatile a = maps.allocate(large);
    float* volatile b = maps.allocate(small);
    maps.deallocate(a, large);
    maps.deallocate(b, small);
    CHECK(allocations.load() - before == 2);
    // And the C library's own functions, aligned or not.
    before = allocations.load();
    void* volatile c = std::malloc(10);
    void* volatile d = std::aligned_alloc(64, 128);
    void* e = nullptr;
    CHECK(posix_memalign(&e, 64, 100) == 0);
    std::free(c), std::free(d), std::free(e);
    CHECK(allocations.load() - before == 3);
}
