// The compute build path (gl::build_path::compute) against the CPU maps built from the same model and
// light: every published method and hybrid, on Sintel and procedural models, directional and point
// lights, long segments across many tiles, hair partly outside the map, and an empty map. Every texel
// is compared: which hold a fragment, states bit for bit, float sums within 1e-6 relative (8-bit levels
// exactly).
#include "gl_test_context.hpp"

#include <hairshadow/gl.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/methods/spec.hpp>

#include "../test_support.hpp"
#include "compute_comparison.hpp"

#include <cmath>
#include <random>


using namespace hairshadow;

namespace {

/// Calls visit(spec, method) for every registered family's examples but the exact map's (float and
/// 8-bit: each kind of placement, accumulation and reconstruction the registry composes).
template <class Visit>
void for_every_method(Visit&& visit) {
    for_each_example([&](const auto& example) {
        using Method = typename std::decay_t<decltype(example)>::method_type;
        if constexpr (!std::is_same_v<Method, exact_reference>) visit(parse_method_spec(example.spec), Method());
    });
}

/// Builds every method on the CPU and on the compute path from `pass`, run last on `model` and
/// `light`, and compares. Returns the texels with a fragment.
long check_every_method_on(const gl::light_pass& pass, const hair_model& model, const light_space& light, const raster_options& options = {}) {
    const auto range = gl::detail::read_range(*pass.textures());
    const auto occupied = test::cpu_occupancy(model, light, options);
    detail::segment_bins bins;
    bins.prepare(model, light, options);
    const auto extent = gl::detail::read_extent(*pass.textures());
    CHECK(extent.nearest == bins.extent().nearest); // the whole map's extent, from the segments as on the CPU
    CHECK(extent.furthest == bins.extent().furthest);
    long texels = -1;
    for_every_method([&]<class Method>(const method_spec& spec, const Method& method) {
        Method cpu = method;
        cpu.build(model, light, options);
        auto on_gl = gl::detail::maps_of_method(method);
        on_gl.build(pass);
        const auto c = test::compare_maps(cpu, on_gl, range, occupied, light.resolution());
        CAPTURE(spec.text, c.occupied, c.occupied_cpu, c.occupancy_off, c.state_off, c.data_off, c.worst);
        CHECK(c.occupied == c.occupied_cpu);
        CHECK(c.occupancy_off == 0);
        CHECK(c.state_off == 0);
        CHECK(c.data_off == 0);
        CHECK(c.worst <= test::float_tolerance);
        texels = c.occupied;
    });
    return texels;
}

/// check_every_method_on a compute light pass run once.
long check_every_method(const hair_model& model, const light_space& light, const raster_options& options = {}) {
    const gl::hair_mesh mesh(model);
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light, options);
    return check_every_method_on(pass, model, light, options);
}

} // namespace

TEST_CASE("compute-built maps equal the CPU maps built from the model, for every method", "[gl][compute]") {
    test::gl_context();
    REQUIRE(gl::compute_path_missing().empty()); // llvmpipe has GL 4.5, and compute needs 4.3 alone
    SECTION("Sintel, directional light, 256x256") {
        const auto model = load_model(test::sintel_hair());
        CHECK(check_every_method(model, light_space::fit(light_spec::directional({0.2f, -1.0f, 0.1f}), model.bounds(), 256)) > 10000);
    }
    SECTION("Sintel, point light, 256x256") {
        const auto model = load_model(test::sintel_hair());
        const auto b = model.bounds();
        const glm::vec3 light = b.center() + glm::vec3(0.3f, 2.5f, 0.5f) * glm::length(b.max - b.min);
        CHECK(check_every_method(model, light_space::fit(light_spec::point(light), b, 256)) > 5000);
    }
    SECTION("curly hair, directional light, 128x128") {
        const auto model = load_model("procedural:curly:strands=300:segments=24");
        CHECK(check_every_method(model, light_space::fit(light_spec::directional({-0.4f, -1.0f, 0.3f}), model.bounds(), 128)) > 2000);
    }
    SECTION("clumped hair, point light, a fixed alpha, 96x96") {
        const auto model = load_model("procedural:clumped:strands=200:segments=16");
        const auto b = model.bounds();
        raster_options options;
        options.fixed_alpha = 0.3f;
        CHECK(check_every_method(model, light_space::fit(light_spec::point(b.center() + glm::vec3(0, 3, 1) * glm::length(b.max - b.min)), b, 96),
                                 options) > 1000);
    }
    SECTION("hair partly outside the map") {
        const auto model = load_model("procedural:straight:strands=400:segments=12");
        auto part = model.bounds();
        part.max = part.min + (part.max - part.min) * 0.5f; // the map covers a corner of the hair
        CHECK(check_every_method(model, light_space::fit(light_spec::directional({0.1f, -1.0f, 0.2f}), part, 64)) > 100);
    }
    SECTION("segments from beyond the guard band, clipped in window space, under a spot light") {
        // From near the light's plane, far off-axis (beyond the +-2^20-texel band), to the map, at many
        // angles, with per-point thickness: the clip's parameters, ends and perspective attributes.
        hair_model model;
        for (int s = 0; s < 48; ++s) {
            const float angle = 0.1309f * float(s);
            const float reach = 40.0f + 2.0f * float(s % 5);
            model.add_strand(std::vector<glm::vec3>{{reach * std::cos(angle), reach * std::sin(angle), -0.002f - 0.0001f * float(s % 3)},
                                                    {0.05f * std::sin(3.0f * angle), 0.05f * std::cos(2.0f * angle), -1.0f - 0.01f * float(s % 4)}});
        }
        for (std::size_t i = 0; i < model.point_count(); ++i) model.thickness.push_back(0.0005f + 0.0003f * float(i % 3));
        const auto light = light_space::fit(light_spec::spot({0, 0, 0}, {0, 0, -1}, 10.0f), model.bounds(), 256);
        REQUIRE(std::abs(light.project(model.points[0]).window.x) > float(1 << 20)); // the band is crossed
        CHECK(check_every_method(model, light) > 2000);
    }
}

TEST_CASE("compute-built maps equal the CPU maps where segments cross many tiles", "[gl][compute]") {
    test::gl_context();
    SECTION("long segments across many tiles, and per-point thickness and opacity") {
        hair_model model; // three points a strand: segments across most of the map, through a dozen tiles each
        for (int s = 0; s < 30; ++s) {
            const std::vector<glm::vec3> points = {
                {0.03f * float(s), 0.0f, 0.0f}, {1.0f - 0.02f * float(s), 1.0f, 0.2f}, {0.1f * float(s % 7), 0.1f, 0.4f + 0.01f * float(s)}};
            model.add_strand(points);
        }
        model.default_thickness = 0.002f;
        for (std::size_t i = 0; i < model.point_count(); ++i) {
            model.thickness.push_back(0.002f + 0.001f * float(i % 5));
            model.transparency.push_back(0.1f * float(i % 7));
        }
        const auto light = light_space::fit(light_spec::directional({0.1f, 0.2f, -1.0f}), model.bounds(), 200);
        const gl::hair_mesh mesh(model);
        gl::light_pass pass(gl::build_path::compute);
        // A run from afar (the map about eight times wider: no long segment) sets the capacity for long pairs
        // that the next run like it (segments and resolution) starts from: a word a segment, too few
        // here, so some long segments are listed in their tiles, the rest in the long list that every
        // tile reads through.
        pass.run(mesh, light_space::fit(light_spec::directional({0.1f, 0.2f, -1.0f}), model.bounds().expanded(5.0f), 200));
        CHECK(pass.compute()->counts().long_pairs == 0);
        pass.run(mesh, light);
        const auto first = pass.compute()->counts();
        CAPTURE(first.pairs, first.long_listed, first.long_binned, first.long_pairs, first.long_capacity);
        CHECK(first.long_listed + first.long_binned >= 40); // segments over more than 4 tiles
        CHECK(first.long_listed > 0);
        CHECK(first.long_binned > 0);
        CHECK(first.long_pairs > first.long_capacity);
        CHECK(check_every_method_on(pass, model, light) > 500);
        // The next sets aside what this one asked for: every long segment in its tiles' lists.
        pass.run(mesh, light);
        const auto second = pass.compute()->counts();
        CHECK(second.long_listed == 0);
        CHECK(second.long_binned == first.long_listed + first.long_binned);
        CHECK(second.long_pairs == first.long_pairs);
        CHECK(second.long_capacity >= second.long_pairs);
        CHECK(check_every_method_on(pass, model, light) > 500);
    }
    SECTION("long segments at every angle, listed in the tiles their lines reach") {
        // Segments of 20 to 250 texels through random points, flat, steep, diagonal and in between, so
        // that many lines pass near a tile's edge: a tile that hs_long_tiles missed would lose fragments.
        std::mt19937 random(43);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        hair_model model;
        for (int s = 0; s < 600; ++s) {
            const float turn = unit(random), spread = unit(random), x = unit(random), y = unit(random), z = unit(random), rise = unit(random);
            const float angle = s % 8 == 0 ? 0.7853982f * float(s / 8 % 8) : 6.2831853f * turn; // every eighth a multiple of 45 degrees
            const float length = 0.08f + 0.9f * spread * spread;
            const glm::vec3 from(x, y, 0.5f * z);
            model.add_strand(std::vector<glm::vec3>{from, from + glm::vec3(length * std::cos(angle), length * std::sin(angle), 0.1f * rise)});
        }
        model.default_thickness = 0.001f;
        aabb box;
        box.min = glm::vec3(0.0f, 0.0f, -0.5f), box.max = glm::vec3(1.0f, 1.0f, 1.0f);
        const auto light = light_space::fit(light_spec::directional({0.0f, 0.0f, -1.0f}), box, 256);
        const gl::hair_mesh mesh(model);
        gl::light_pass pass(gl::build_path::compute);
        pass.run(mesh, light); // the first run at a resolution measures what long segments ask for first
        const auto counts = pass.compute()->counts();
        CAPTURE(counts.pairs, counts.long_listed, counts.long_binned, counts.long_pairs, counts.long_capacity);
        CHECK(counts.long_listed == 0);
        CHECK(counts.long_binned >= 300);
        CHECK(check_every_method_on(pass, model, light) > 15000);
    }
}

TEST_CASE("a light pass takes one optical depth a segment where every segment has one alpha", "[gl][compute]") {
    test::gl_context();
    hair_model model = load_model("procedural:straight:strands=40:segments=6");
    model.thickness.clear(), model.transparency.clear();
    model.default_thickness = 0.002f;
    const auto box = model.bounds();
    const auto directional = light_space::fit(light_spec::directional({0.1f, -1.0f, 0.2f}), box, 64);
    const auto point = light_space::fit(light_spec::point(box.center() + glm::vec3(0, 3, 1) * glm::length(box.max - box.min)), box, 64);
    gl::light_pass pass(gl::build_path::compute);
    const auto one_alpha = [&](const gl::hair_mesh& mesh, const light_space& light, const raster_options& options) {
        pass.run(mesh, light, options);
        return pass.compute()->one_alpha();
    };
    raster_options weighted, unweighted, fixed;
    unweighted.depth_weighting = false;
    fixed.fixed_alpha = 0.4f;
    const gl::hair_mesh uniform(model);
    CHECK(uniform.uniform_attributes());
    CHECK(one_alpha(uniform, directional, weighted));
    CHECK_FALSE(one_alpha(uniform, point, weighted)); // the footprint, and so alpha, changes with depth
    CHECK(one_alpha(uniform, point, unweighted));
    for (std::size_t i = 0; i < model.point_count(); ++i) model.thickness.push_back(0.001f + 0.001f * float(i % 3));
    const gl::hair_mesh varying(model);
    CHECK_FALSE(varying.uniform_attributes());
    CHECK_FALSE(one_alpha(varying, directional, weighted));
    CHECK(one_alpha(varying, point, fixed));
    // Either form gives the CPU's maps: the sections above run both (Sintel's directional light and the
    // fixed alpha in one form, the point light and per-point thickness in the other).
}

TEST_CASE("the compute path builds an empty map where no hair reaches it", "[gl][compute]") {
    test::gl_context();
    const auto model = load_model("procedural:straight:strands=50:segments=8");
    auto away = model.bounds();
    const glm::vec3 shift(0, 0, 10.0f * glm::length(away.max - away.min));
    away.min += shift, away.max += shift;
    const auto light = light_space::fit(light_spec::directional({0, 0, -1}), away, 32);
    const gl::hair_mesh mesh(model);
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light);
    const auto extent = gl::detail::read_extent(*pass.textures());
    CHECK(extent.nearest == 0.0f);
    CHECK(extent.furthest == 0.0f);
    const auto counts = pass.compute()->counts();
    CHECK(counts.pairs == 0);
    CHECK(counts.long_listed + counts.long_binned == 0);
    gl::maps<occupancy_maps<128, 4>> occ;
    occ.build(pass);
    using texel = occupancy_maps<128, 4>::texel_maps;
    for (const auto& t : occ.read_back()) CHECK(t == texel{});
    CHECK(check_every_method(model, light) == 0);
}

TEST_CASE("the GLSL look-up of compute-built maps gives the CPU query", "[gl][compute][lookup]") {
    test::gl_context();
    const auto model = load_model(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1.0f, 0.1f}), model.bounds(), 256);
    const auto fragments = rasterize(model, light);
    const auto queries = test::texel_centre_queries(fragments, light, 3);
    REQUIRE(queries.size() >= 2000);
    const gl::hair_mesh mesh(model);
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light);
    for_every_method([&]<class Method>(const method_spec& spec, const Method& method) {
        auto on_gl = gl::detail::maps_of_method(method);
        on_gl.build(pass);
        Method cpu = method;
        cpu.build(model, light);
        const auto on_gpu = test::gl_lookup(on_gl.lookup_source(), [&](GLuint p) { on_gl.bind_lookup(p); }, queries);
        std::vector<float> on_cpu(queries.size());
        cpu.transmittance(queries, on_cpu);
        float worst = 0.0f;
        for (std::size_t i = 0; i < queries.size(); ++i) worst = std::max(worst, std::abs(on_gpu[i] - on_cpu[i]));
        CAPTURE(spec.text, worst);
        CHECK(worst < 1e-4f);
    });
}

TEST_CASE("two compute builds give identical maps, and the default path is compute", "[gl][compute][determinism]") {
    test::gl_context();
    const auto model = load_model("procedural:curly:strands=300:segments=24");
    const auto light = light_space::fit(light_spec::directional({-0.4f, -1.0f, 0.3f}), model.bounds(), 128);
    const gl::hair_mesh mesh(model);
    gl::maps<density_clustering<4>> first, second;
    gl::maps<occupancy_maps<128, 4>> occ_first, occ_second;
    CHECK(first.path() == gl::build_path::compute);
    CHECK(gl::light_pass().path() == gl::build_path::compute);
    first.build(mesh, light);
    second.build(mesh, light);
    occ_first.build(mesh, light);
    occ_second.build(mesh, light);
    CHECK(first.read_back() == second.read_back());
    CHECK(occ_first.read_back() == occ_second.read_back());
    // The raster path's maps differ: GL draws its own lines.
    gl::maps<occupancy_maps<128, 4>> raster;
    raster.set_build_path(gl::build_path::raster);
    raster.build(mesh, light);
    CHECK(raster.path() == gl::build_path::raster);
    CHECK(raster.read_back() != occ_first.read_back());
}

TEST_CASE("the compute path refuses wide lines with a feature error", "[gl][compute][errors]") {
    test::gl_context();
    const auto model = test::grid_model(10, 4);
    const gl::hair_mesh mesh(model);
    raster_options options;
    options.wide_line_width = 4.0f;
    gl::light_pass pass(gl::build_path::compute);
    CHECK_THROWS_AS(pass.run(mesh, light_space::fit(light_spec::directional({0, -1, 0}), model.bounds(), 32), options), gl::feature_error);
}
