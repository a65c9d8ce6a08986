// The published methods and hybrids measured against the exact reference: the papers' claims as
// tests on the Sintel model and the procedural straight and curly models at 512x512.
#include "test_support.hpp"

#include <hairshadow/hairshadow.hpp>

#include <catch2/catch.hpp>

#include <cstring>

using namespace hairshadow;

namespace {

struct measured_scene {
    hair_model model;
    light_space light;
    fragment_buffer fragments;
    std::vector<float> exact; ///< exact transmittance at the model's points
};

measured_scene measure(const std::string& name) {
    measured_scene s;
    if (name == "sintel") s.model = read_tfx(test::sintel_hair());
    else s.model = make_procedural({.style = name == "curly" ? hair_style::curly : hair_style::straight, .strands = 4000, .segments = 32});
    s.light = light_space::fit(light_spec::directional({0, -1, -1}), s.model.bounds(), 512);
    s.fragments = rasterize(s.model, s.light);
    const deep_shadow_map exact(s.fragments, s.light);
    s.exact.resize(s.model.point_count());
    exact.transmittance(s.model.points, s.exact);
    return s;
}

/// Mean |T - T_exact| over the model's points.
template <class Method>
double mean_error(const measured_scene& s, Method method = Method()) {
    method.build(s.fragments, s.light);
    std::vector<float> t(s.model.point_count());
    method.transmittance(s.model.points, t);
    double sum = 0;
    for (std::size_t i = 0; i < t.size(); ++i) sum += std::abs(t[i] - s.exact[i]);
    return sum / double(t.size());
}

} // namespace

TEST_CASE("the papers' claims on Sintel, straight and curly hair at 512x512", "[methods][claims]") {
    const std::string name = GENERATE("sintel", "straight", "curly");
    CAPTURE(name);
    const auto s = measure(name);
    const double osm16 = mean_error<opacity_shadow_maps<16>>(s), osm64 = mean_error<opacity_shadow_maps<64>>(s),
                 osm256 = mean_error<opacity_shadow_maps<256>>(s);
    const double dom3 = mean_error<deep_opacity_maps<3>>(s), dom4 = mean_error<deep_opacity_maps<4>>(s);
    const double dc4 = mean_error<density_clustering<4>>(s), occ = mean_error<occupancy_maps<128, 4>>(s);
    WARN(name << ": osm16 " << osm16 << " osm64 " << osm64 << " osm256 " << osm256 << " dom3 " << dom3 << " dom4 " << dom4 << " dc4 "
              << dc4 << " occ128/4 " << occ);

    // Kim & Neumann: more maps, less error.
    CHECK(osm64 < osm16);
    CHECK(osm256 < osm64);
    // Mertens et al.: 4 clusters beat 16 uniform slices.
    CHECK(dc4 < osm16);
    // Sintorn & Assarsson: occupancy maps beat deep opacity maps of 4 layers.
    CHECK(occ < dom4);
    // Yuksel & Keyser claim that 3 deep layers beat 16 opacity maps. On our data the mean error over
    // all points does not bear it out, for any layer depth we tried (docs/methods.md): 3 linear
    // layers cannot follow the transmittance deep inside the hair. What holds is recorded instead:
    // DOM's error is larger overall, and it is exact for directly lit hair (the next test).
    CHECK(dom3 > osm16);
}

TEST_CASE("deep opacity maps light each texel's first fragment fully, opacity maps do not", "[methods][claims]") {
    const std::string name = GENERATE("sintel", "straight", "curly");
    CAPTURE(name);
    const auto s = measure(name);
    deep_opacity_maps<3> dom;
    dom.build(s.fragments, s.light);
    opacity_shadow_maps<16> osm;
    osm.build(s.fragments, s.light);
    float worst_dom = 0, worst_osm = 0;
    int texels = 0;
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 512; ++x) {
            const auto frags = s.fragments.texel(x, y);
            if (frags.empty()) continue;
            float z0 = frags[0].depth;
            for (const auto& f : frags) z0 = std::min(z0, f.depth);
            worst_dom = std::max(worst_dom, 1.0f - dom.transmittance(x, y, z0));
            worst_osm = std::max(worst_osm, 1.0f - osm.transmittance(x, y, z0));
            ++texels;
        }
    CHECK(texels > 10000);
    CHECK(worst_dom <= 1e-6f);
    CHECK(worst_osm > 0.1f);
}

TEST_CASE("occupancy maps equal the exact reference at slab boundaries", "[methods][claims]") {
    const std::string name = GENERATE("sintel", "curly");
    CAPTURE(name);
    const auto s = measure(name);
    occupancy_maps<128, 4> occ;
    occ.build(s.fragments, s.light);
    const deep_shadow_map exact(s.fragments, s.light);
    int checked = 0, within = 0;
    float worst = 0;
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 512; ++x) {
            const auto& state = occ.texel(x, y).placement;
            if (!(state.furthest > state.nearest)) continue;
            for (int b = 0; b <= 4; ++b) {
                // A slab boundary, 32 b slices into the range (the far end for b = 4).
                const float depth = b == 4 ? detail::just_above(state.furthest) : occ.placement().boundary(state, 32 * b);
                const float omega_occ = occ.optical_depth(x, y, depth), omega = exact.optical_depth(x, y, depth);
                const float error = std::abs(omega_occ - omega);
                worst = std::max(worst, error);
                within += error <= 1e-4f * std::max(1.0f, omega);
                ++checked;
            }
        }
    CAPTURE(worst);
    CHECK(checked > 50000);
    CHECK(within == checked);
}

TEST_CASE("every method gives the same maps for any thread count", "[methods][determinism]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto light = light_space::fit(light_spec::directional({0.2f, -1, -0.4f}), m.bounds(), 256);
    const auto fb = rasterize(m, light);
    auto same_maps = [&](auto method) {
        auto other = method;
        method.build(fb, light, execution{1});
        other.build(fb, light, execution{3});
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x)
                if (std::memcmp(&method.texel(x, y), &other.texel(x, y), sizeof(method.texel(x, y))) != 0) return false;
        return true;
    };
    CHECK(same_maps(opacity_shadow_maps<16>()));
    CHECK(same_maps(opacity_shadow_maps<16, gamma_spacing, emulated_8bit>()));
    CHECK(same_maps(deep_opacity_maps<3>()));
    CHECK(same_maps(density_clustering<4>()));
    CHECK(same_maps(occupancy_maps<128, 4>()));
    CHECK(same_maps(deep_occupancy_maps<128, 4>()));
    CHECK(same_maps(deep_opacity_maps_8bit<3>()));
}

TEST_CASE("hybrids compose from existing policies and behave", "[methods][hybrid]") {
    const auto s = measure("curly");
    // 8-bit deep opacity maps: close to the float ones, a little worse, never better than the exact.
    const double dom3 = mean_error<deep_opacity_maps<3>>(s), dom3_8bit = mean_error<deep_opacity_maps_8bit<3>>(s);
    CHECK(dom3_8bit >= dom3 - 1e-3);
    CHECK(dom3_8bit < dom3 + 0.02);
    STATIC_REQUIRE(deep_opacity_maps_8bit<3>::texel_bytes() == 8); // z0 + 3 bytes, padded
    // Occupancy bits in deep-opacity layers: exact at each texel's first fragment like DOM, and far
    // closer to the truth than DOM's three layers.
    deep_occupancy_maps<128, 4> docc;
    docc.build(s.fragments, s.light);
    for (int y = 100; y < 400; y += 37)
        for (int x = 100; x < 400; x += 41)
            if (!s.fragments.texel(x, y).empty()) CHECK(docc.transmittance(x, y, docc.texel(x, y).placement.z0) == 1.0f);
    const double docc_error = mean_error<deep_occupancy_maps<128, 4>>(s);
    CHECK(docc_error < dom3);
    // Opacity maps in each texel's depth range beat global ones of the same count.
    CHECK(mean_error<range_opacity_maps<16>>(s) < mean_error<opacity_shadow_maps<16>>(s));
}

TEST_CASE("queries can be box-filtered and jittered", "[methods][query]") {
    const auto s = measure("straight");
    occupancy_maps<128, 4> occ;
    occ.build(s.fragments, s.light);
    const glm::vec3 p = s.model.points[777];
    const auto td = s.light.locate(p);
    REQUIRE(td);
    float sum = 0;
    int n = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) sum += occ.optical_depth(td->x + dx, td->y + dy, td->depth), ++n;
    CHECK(occ.transmittance(p, {.box_filter = true}) == Approx(std::exp(-sum / float(n))));
    const float jittered = occ.transmittance(p, {.jitter = true});
    CHECK(jittered == occ.transmittance(p, {.jitter = true})); // deterministic
    int moved = 0;
    for (std::size_t i = 0; i < s.model.point_count(); i += 101) moved += occ.transmittance(s.model.points[i], {.jitter = true}) != occ.transmittance(s.model.points[i]);
    CHECK(moved > 0);
    CHECK(occ.transmittance(p, {.depth_bias = 1.0f}) == 1.0f); // moved in front of everything
}

TEST_CASE("adopted maps answer like the maps they came from, and must fit the light", "[methods]") {
    const auto model = test::grid_model(40, 8);
    const auto light = light_space::fit(light_spec::directional({0, 0, -1}), model.bounds(), 32);
    const auto fragments = rasterize(model, light);
    deep_opacity_maps<3> built;
    built.build(fragments, light);
    std::vector<deep_opacity_maps<3>::texel_maps> texels;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) texels.push_back(built.texel(x, y));
    deep_opacity_maps<3> adopted;
    adopted.adopt(light, built.placement(), texels);
    for (int y = 0; y < 32; y += 3)
        for (int x = 0; x < 32; x += 3)
            for (float depth : {0.0f, 0.3f, 0.6f, 1.0f}) CHECK(adopted.transmittance(x, y, depth) == built.transmittance(x, y, depth));
    texels.pop_back();
    CHECK_THROWS_AS(adopted.adopt(light, built.placement(), texels), argument_error);
}

TEST_CASE("a method spec's counts are whole numbers written without a sign or a leading zero", "[methods][spec]") {
    CHECK(parse_method_spec("dom:3").fields == std::vector<std::string>{"3"});
    CHECK(parse_method_spec("osm:16:gamma").fields == std::vector<std::string>{"16", "gamma"});
    const auto eight_bit = parse_method_spec("occ:128:4:8bit");
    CHECK(eight_bit.family == "occ");
    CHECK(eight_bit.fields == std::vector<std::string>{"128", "4"});
    CHECK(eight_bit.accumulation == "8bit"); // a parameter like the others
    CHECK(parse_method_spec("rosm:8").accumulation == "float");
    for (const char* bad : {"dom:03", "dc:04", "osm:016", "occ:0128:4", "occ:128:04", "docc:128:004", "rosm:08", "dom:00", "dom:+3", "dom:3.0",
                            "dom: 3", "dom:3 ", "osm:1e1", "dom:-3"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
    CHECK_THROWS_WITH(parse_method_spec("dom:03"), Catch::Contains("'03' has a leading zero"));
}
