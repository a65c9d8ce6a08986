#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

using namespace hairshadow;

namespace {

/// A one-texel buffer holding fragments at `depths`, each of optical depth b (alpha = 1 - e^-b).
fragment_buffer one_texel(std::initializer_list<float> depths, float b = 1.0f) {
    std::vector<fragment> f;
    for (float d : depths) f.push_back({d, float(1.0 - std::exp(-double(b)))});
    return fragment_buffer(1, {0, f.size()}, f);
}

light_space one_texel_light() {
    aabb box;
    box.add({0, 0, 0});
    box.add({1, 1, 1});
    return light_space::fit(light_spec::directional({0, 0, -1}), box, 1);
}

template <class Method>
Method built(const fragment_buffer& fb, Method m = Method()) {
    m.build(fb, one_texel_light());
    return m;
}

} // namespace

TEST_CASE("float accumulation sums optical depths as they are", "[policy][accumulation]") {
    using A = float_accumulation;
    CHECK(A::decode(A::store(A::add(A::add(0.0f, 0.25f), 0.5f))) == 0.75f);
    CHECK(A::combine(1.0f, 2.0f) == 3.0f);
}

TEST_CASE("emulated 8-bit accumulation quantises every add and saturates", "[policy][accumulation]") {
    using A = emulated_8bit;
    CHECK(std::exp(-A::kappa) == Approx(1.0f / 256.0f)); // exp(-kappa) = 2^-8
    const float step = A::kappa / 255.0f;                 // the optical depth of one 8-bit step
    CHECK(A::quantise(3.4f * step) == 3);
    CHECK(A::quantise(3.6f * step) == 4);
    CHECK(A::quantise(0.4f * step) == 0); // a faint fragment is lost, as in an RGBA8 target
    CHECK(A::quantise(100.0f) == 255);
    CHECK(A::store(A::add(A::add(0, 200.0f * step), 100.0f * step)) == 255); // saturates
    CHECK(A::decode(255) == Approx(A::kappa));
    CHECK(A::decode(A::store(A::add(0, 10.0f * step))) == Approx(10.0f * step));
}

TEST_CASE("planar slices: boundaries, assignment and interpolation", "[policy][placement][osm]") {
    const auto fb = one_texel({0.2f, 0.25f, 0.41f, 0.6f});
    uniform_slices<4> u;
    u.prepare(extent_of(fb));
    const uniform_slices<4>::texel_state s{};
    CHECK(u.boundary(s, 0) == 0.2f);
    CHECK(u.boundary(s, 2) == Approx(0.4f));
    CHECK(u.assign(s, 0.25f) == 0);
    CHECK(u.assign(s, 0.41f) == 2);
    CHECK(u.assign(s, 0.6f) == 3); // the furthest fragment lies just inside the last slice
    CHECK(u.locate(s, 0.1f).index == -1);
    CHECK(u.locate(s, 0.7f).index == 4);
    gamma_slices<4> g;
    g.prepare(extent_of(fb));
    const gamma_slices<4>::texel_state gs{};
    CHECK(g.boundary(gs, 1) == Approx(0.2f + 0.4f / 16.0f)); // (1/4)^2 of the range
    CHECK(g.boundary(gs, 2) == Approx(0.3f));
    CHECK(g.assign(gs, 0.25f) == 1);

    // Maps hold the optical depth in front of their far boundary; a query interpolates in depth.
    const auto osm = built<opacity_shadow_maps<4>>(fb);
    CHECK(osm.stored_optical_depth(0, 0, 0) == 2.0f); // 0.2 and 0.25 lie in [0.2, 0.3)
    CHECK(osm.stored_optical_depth(0, 0, 1) == 2.0f);
    CHECK(osm.stored_optical_depth(0, 0, 2) == 3.0f); // 0.41
    CHECK(osm.stored_optical_depth(0, 0, 3) == 4.0f);
    CHECK(osm.optical_depth(0, 0, 0.2f) == 0.0f);
    CHECK(osm.optical_depth(0, 0, 0.25f) == Approx(1.0f)); // half-way through slice 0
    CHECK(osm.optical_depth(0, 0, 0.45f) == Approx(2.5f)); // half-way through slice 2
    CHECK(osm.optical_depth(0, 0, 0.9f) == 4.0f);
}

TEST_CASE("per-pixel depth layers start at the first fragment and grow linearly", "[policy][placement][dom]") {
    const auto fb = one_texel({0.3f, 0.31f, 0.36f, 0.6f, 0.9f});
    per_pixel_depth<3> p(0.3f);
    p.prepare(extent_of(fb));
    per_pixel_depth<3>::texel_state s;
    p.prepare_texel(fb.texel(0, 0), s);
    CHECK(s.z0 == 0.3f);
    // Linearly increasing sizes: d_k = d_K k (k + 1) / (K (K + 1)) = 0.3 x {0, 1/6, 1/2, 1}.
    CHECK(p.boundary(s, 1) == Approx(0.35f));
    CHECK(p.boundary(s, 2) == Approx(0.45f));
    CHECK(p.boundary(s, 3) == Approx(0.6f));
    CHECK(p.assign(s, 0.31f) == 0);
    CHECK(p.assign(s, 0.36f) == 1);
    CHECK(p.assign(s, 0.9f) == 2); // beyond the last layer: clamped into it (the paper's choice)
    per_pixel_depth<3, layer_sizes::linear, beyond_last_layer::ignore> ignore(0.3f);
    ignore.prepare(extent_of(fb));
    CHECK(ignore.assign({0.3f}, 0.9f) == -1);
    per_pixel_depth<3, layer_sizes::uniform, beyond_last_layer::extend> extend(0.3f);
    extend.prepare(extent_of(fb));
    decltype(extend)::texel_state e;
    extend.prepare_texel(fb.texel(0, 0), e);
    CHECK(extend.boundary(e, 3) > 0.9f); // stretched to reach the last fragment
    CHECK(extend.boundary(e, 1) == Approx(0.3f + (extend.boundary(e, 3) - 0.3f) / 3.0f));

    const auto dom = built(fb, deep_opacity_maps<3>(per_pixel_depth<3>(0.3f)));
    CHECK(dom.optical_depth(0, 0, 0.3f) == 0.0f); // T = 1 at the first fragment
    CHECK(dom.stored_optical_depth(0, 0, 0) == 2.0f);
    CHECK(dom.stored_optical_depth(0, 0, 1) == 3.0f);
    CHECK(dom.stored_optical_depth(0, 0, 2) == 5.0f); // 0.6 and 0.9 clamp into the last layer
    CHECK(dom.optical_depth(0, 0, 0.4f) == Approx(2.5f));
    CHECK(dom.optical_depth(0, 0, 0.95f) == 5.0f);
}

TEST_CASE("density clustering: one k-means step, sqrt(3) sigma bins, split overlaps", "[policy][placement][dc]") {
    SECTION("two separate clusters") {
        const auto fb = one_texel({0.1f, 0.12f, 0.5f, 0.52f});
        clustered<2> c;
        clustered<2>::texel_state s;
        c.prepare_texel(fb.texel(0, 0), s);
        CHECK(s.mean[0] == Approx(0.11f));
        CHECK(s.mean[1] == Approx(0.51f));
        CHECK(s.sigma[0] == Approx(0.01f).epsilon(1e-3));
        const auto bins = c.bins(s);
        CHECK(bins[0].lo == Approx(0.11f - std::sqrt(3.0f) * 0.01f).epsilon(1e-4));
        CHECK(bins[1].hi == Approx(0.51f + std::sqrt(3.0f) * 0.01f).epsilon(1e-4));
        const auto dc = built<density_clustering<2>>(fb);
        CHECK(dc.optical_depth(0, 0, 0.05f) == 0.0f);
        CHECK(dc.optical_depth(0, 0, 0.11f) == Approx(1.0f).epsilon(1e-3)); // half-way through bin 0
        CHECK(dc.optical_depth(0, 0, 0.3f) == Approx(2.0f));                // between the bins
        CHECK(dc.optical_depth(0, 0, 0.9f) == Approx(4.0f));
    }
    SECTION("overlapping bins meet at the midpoint") {
        // Centres 0.15 and 0.25; 0.2 is equally near both and goes to the first.
        const auto fb = one_texel({0.1f, 0.2f, 0.22f, 0.3f});
        clustered<2> c;
        clustered<2>::texel_state s;
        c.prepare_texel(fb.texel(0, 0), s);
        CHECK(s.mean[0] == Approx(0.15f));
        CHECK(s.mean[1] == Approx(0.26f));
        const float r1 = 0.15f + std::sqrt(3.0f) * 0.05f, l2 = 0.26f - std::sqrt(3.0f) * 0.04f;
        REQUIRE(r1 > l2);
        const auto bins = c.bins(s);
        CHECK(bins[0].hi == Approx(0.5f * (r1 + l2)).epsilon(1e-4));
        CHECK(bins[1].lo == bins[0].hi);
        CHECK(c.assign(s, 0.2f) == 0);
        CHECK(c.assign(s, 0.22f) == 1);
    }
    SECTION("a fragment outside every bin goes to the nearest cluster") {
        clustered<2> c;
        clustered<2>::texel_state s;
        s.mean = {0.2f, 0.6f};
        s.sigma = {0.01f, 0.01f};
        CHECK(c.assign(s, 0.35f) == 0);
        CHECK(c.assign(s, 0.45f) == 1);
        s.sigma[0] = -1.0f; // an empty cluster takes nothing
        CHECK(c.assign(s, 0.21f) == 1);
    }
}

TEST_CASE("occupancy: set bits share their slab's sum, exact at slab boundaries", "[policy][reconstruction][occ]") {
    // 64 slices in [0, 1], two slabs of 32. Slab 0: depths 0, 0.1, 0.1 (slices 0, 6); slab 1: 0.6, 1.0
    // (slices 38, 63).
    const auto fb = one_texel({0.0f, 0.1f, 0.1f, 0.6f, 1.0f});
    const auto occ = built<occupancy_maps<64, 2>>(fb);
    const auto& t = occ.texel(0, 0);
    CHECK(t.data.bits[0] == ((1u << 0) | (1u << 6)));
    CHECK(t.data.bits[1] == ((1u << (38 - 32)) | (1u << (63 - 32))));
    CHECK(t.data.slabs[0] == 3.0f);
    CHECK(t.data.slabs[1] == 2.0f);
    CHECK(occ.optical_depth(0, 0, 0.0f) == 0.0f);
    CHECK(occ.optical_depth(0, 0, 3.2f / 64.0f) == Approx(1.5f));          // one set bit before, worth 3 / 2
    CHECK(occ.optical_depth(0, 0, 6.5f / 64.0f) == Approx(1.5f * 1.5f));   // half-way through the second
    CHECK(occ.optical_depth(0, 0, 0.5f) == 3.0f);                          // slab boundary: exact
    CHECK(occ.optical_depth(0, 0, 0.99f) == Approx(4.36f));                // slice 63, 0.36 in; one bit before
    CHECK(occ.optical_depth(0, 0, 1.5f) == 5.0f);
    CHECK(occupancy_bitcount<2>::count_bits(t.data.bits, 0, 64) == 4);
    CHECK(occupancy_bitcount<2>::count_bits(t.data.bits, 1, 39) == 2);
}

namespace {
/// An accumulation that forgot decode().
struct no_decode {
    using value_type = float;
    using sum_type = float;
    static float add(float s, float) { return s; }
    static float combine(float a, float) { return a; }
    static float store(float s) { return s; }
    static constexpr std::string_view glsl_name = "x";
};
} // namespace

TEST_CASE("policy compositions are checked by concepts", "[policy][concepts]") {
    STATIC_REQUIRE(placement_policy<uniform_slices<16>>);
    STATIC_REQUIRE(placement_policy<gamma_slices<8>>);
    STATIC_REQUIRE(placement_policy<per_pixel_depth<3>>);
    STATIC_REQUIRE(placement_policy<clustered<4>>);
    STATIC_REQUIRE(placement_policy<depth_range<128>>);
    STATIC_REQUIRE_FALSE(placement_policy<int>);
    STATIC_REQUIRE_FALSE(placement_policy<float_accumulation>);
    STATIC_REQUIRE(accumulation_policy<float_accumulation>);
    STATIC_REQUIRE(accumulation_policy<emulated_8bit>);
    STATIC_REQUIRE_FALSE(accumulation_policy<no_decode>);
    STATIC_REQUIRE(reconstruction_policy<interpolation, clustered<4>, float_accumulation>);
    STATIC_REQUIRE(reconstruction_policy<occupancy_bitcount<4>, depth_range<128>, emulated_8bit>);
    // Occupancy bits need contiguous slices, a multiple of 32 and of the slab count.
    STATIC_REQUIRE(occupancy_bitcount<4>::accepts<depth_range<128>>);
    STATIC_REQUIRE(occupancy_bitcount<4>::accepts<per_pixel_depth<128, layer_sizes::uniform>>);
    STATIC_REQUIRE_FALSE(occupancy_bitcount<4>::accepts<clustered<4>>);
    STATIC_REQUIRE_FALSE(occupancy_bitcount<4>::accepts<depth_range<100>>);
    STATIC_REQUIRE_FALSE(occupancy_bitcount<3>::accepts<depth_range<128>>);
    STATIC_REQUIRE(interpolation::accepts<clustered<4>>);
}

TEST_CASE("maps hold what the papers store", "[policy][memory]") {
    constexpr std::size_t texels = 512 * 512;
    STATIC_REQUIRE(deep_opacity_maps<3>::texel_bytes() == 16); // z0 + 3 layers: one RGBA32F texel
    STATIC_REQUIRE(occupancy_maps<128, 4>::texel_bytes() == 40); // range 8 + 128 bits 16 + 4 slabs 16
    STATIC_REQUIRE(opacity_shadow_maps<16>::texel_bytes() == 64);
    STATIC_REQUIRE(density_clustering<4>::texel_bytes() == 48); // means, sigmas and the histogram
    opacity_shadow_maps<16> osm;
    deep_opacity_maps<3> dom;
    occupancy_maps<128, 4> occ;
    const auto m = make_procedural({.strands = 300, .segments = 8});
    const auto light = light_space::fit(light_spec::directional({0, -1, 0}), m.bounds(), 512);
    const auto fb = rasterize(m, light);
    osm.build(fb, light);
    dom.build(fb, light);
    occ.build(fb, light);
    CHECK(dom.memory_bytes() == texels * 16 + sizeof(float));       // 4 MiB plus d_K
    CHECK(occ.memory_bytes() == texels * 40);                        // 10 MiB, as in Sintorn & Assarsson
    CHECK(occ.memory_bytes() <= 10u * 1024 * 1024);
    CHECK(osm.memory_bytes() == texels * 16 * 4 + (16 + 3) * sizeof(float)); // N MiB plus the boundaries
}

TEST_CASE("8-bit sums saturate at every step", "[policy][accumulation]") {
    using A = emulated_8bit;
    CHECK(A::add(250, A::kappa) == 255);
    CHECK(A::combine(200, 200) == 255);
    A::sum_type s = 0;
    for (int i = 0; i < 10000000; ++i) s = A::add(s, A::kappa);
    CHECK(A::store(s) == 255);
}

TEST_CASE("density clustering bins stay ordered when splits cascade", "[policy][placement][dc]") {
    clustered<3> c;
    clustered<3>::texel_state s;
    s.mean = {0.0f, 1.0f, 1.2f};
    s.sigma = {3.0f, 0.5f, 0.01f};
    const auto bins = c.bins(s);
    for (const auto& b : bins) CHECK(b.lo <= b.hi);
    CHECK(bins[0].hi <= bins[1].lo);
    CHECK(bins[1].hi <= bins[2].lo);
}

TEST_CASE("a method queried before it is built sees no shadow", "[policy]") {
    const deep_opacity_maps<3> dom;
    CHECK(dom.transmittance(glm::vec3(0, 0, 0)) == 1.0f);
}

namespace {

/// interpolation::build of texels whose fragments share one optical depth (counted, then summed from a
/// table) against the same fragments added one by one in order, as the build does with mixed ones, on
/// each instruction path; with `Fragment` = fragment, from alphas. Returns the texels whose maps
/// differ; `one_b` is how many of a path's texels share one optical depth.
template <class Placement, class Accumulation, class Fragment = optical_fragment>
std::size_t differing_counted_builds(std::size_t& one_b) {
    Placement placement;
    placement.prepare(depth_extent{0.1f, 0.9f});
    random_stream random(11);
    const auto make = [](float depth, float b) {
        if constexpr (std::is_same_v<Fragment, fragment>) return fragment{depth, float(1.0 - std::exp(-double(b)))};
        else return optical_fragment{depth, b};
    };
    std::vector<std::vector<Fragment>> texels;
    for (const int n : {1, 2, 5, 16, 17, 47, 64, 65, 200, 1500}) {
        for (const float b : {0.1f, 0.0123f, 1.7f, 0.0f, -0.0f}) {
            std::vector<Fragment> t;
            for (int i = 0; i < n; ++i) t.push_back(make(random.uniform(0.1f, 0.9f), b));
            texels.push_back(t);
        }
        std::vector<Fragment> mixed;
        for (int i = 0; i < n; ++i) mixed.push_back(make(random.uniform(0.1f, 0.9f), random.uniform(0.0f, 1.0f)));
        texels.push_back(mixed);
        if (n > 1) { // one b but the last: the per-fragment path
            std::vector<Fragment> last_differs = texels[texels.size() - 6];
            last_differs.back() = make(last_differs.back().depth, 0.2f);
            texels.push_back(last_differs);
        }
    }
    std::vector<instruction_set> paths{instruction_set::scalar};
    if (detail::cpu_has_avx512()) paths.push_back(instruction_set::avx512);
    std::size_t differing = 0;
    one_b = 0;
    for (const auto& t : texels)
        one_b += std::all_of(t.begin(), t.end(), [&](const Fragment& f) { return fragment_optical_depth(f) == fragment_optical_depth(t[0]); });
    for (const auto path : paths)
        for (const auto& t : texels) {
            const std::span<const Fragment> in(t);
            typename Placement::texel_state state;
            placement.prepare_texel(in, state);
            interpolation::storage<Placement, Accumulation> built, expected;
            interpolation::build<Placement, Accumulation>(placement, state, in, built, path);
            interpolation::accumulator<Placement, Accumulation> sums{};
            for (const auto& f : t) interpolation::accumulate<Placement, Accumulation>(sums, placement.assign(state, f.depth), fragment_optical_depth(f));
            interpolation::finish<Placement, Accumulation>(sums, expected);
            differing += !(built == expected);
        }
    return differing;
}

} // namespace

TEST_CASE("a texel of one optical depth sums its layers from their counts, bit for bit", "[policy][reconstruction]") {
    std::size_t one_b = 0;
    CHECK(differing_counted_builds<clustered<4>, float_accumulation>(one_b) == 0);
    CHECK(one_b == 51); // ten sizes, five b each, and the mixed texel of one fragment
    CHECK(differing_counted_builds<clustered<4>, emulated_8bit>(one_b) == 0);
    CHECK(differing_counted_builds<clustered<4>, float_accumulation, fragment>(one_b) == 0); // from alphas
    CHECK(differing_counted_builds<clustered<16>, float_accumulation>(one_b) == 0);
    CHECK(differing_counted_builds<per_pixel_depth<3>, float_accumulation>(one_b) == 0);
    CHECK(differing_counted_builds<per_pixel_depth<3>, emulated_8bit>(one_b) == 0);
    // Fragments past the last layer go in none (layer -1).
    CHECK(differing_counted_builds<per_pixel_depth<3, layer_sizes::linear, beyond_last_layer::ignore>, float_accumulation>(one_b) == 0);
    CHECK(differing_counted_builds<planar_slices<16>, float_accumulation>(one_b) == 0);
    CHECK(differing_counted_builds<planar_slices<64>, float_accumulation>(one_b) == 0); // many layers: counted one by one
    // A sum of n equal adds is not n times b: the table adds them one by one.
    float sum = 0.0f;
    for (int i = 0; i < 1500; ++i) sum += 0.0123f;
    CHECK(sum != 1500.0f * 0.0123f);
    detail::repeated_sums<float_accumulation> table;
    table.use(0.0123f);
    CHECK(table(1500) == sum);
    CHECK(table(0) == 0.0f);
    table.use(0.5f); // another b starts afresh
    CHECK(table(3) == 1.5f);
    table.use(0.0123f); // and the first again, past the table's end
    CHECK(table(1500) == sum);
}
