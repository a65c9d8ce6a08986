// The method registrations (methods/registered.hpp): every family's examples parse and make, through
// the run-time registry, the method the family says; the grammar, the command line's lists and the
// fuzz dictionary come from the families; a spec's accumulation is a parameter like the others.
#include "test_support.hpp"

#include <hairshadow/methods/registry.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <sstream>
#include <type_traits>

using namespace hairshadow;

TEST_CASE("every family's examples parse and make the method the family says", "[methods][spec][registry]") {
    std::set<std::string> families;
    std::size_t examples = 0;
    for_each_example([&](const auto& example) {
        using Method = typename std::decay_t<decltype(example)>::method_type;
        CAPTURE(example.spec);
        const auto spec = parse_method_spec(example.spec);
        CHECK(spec.text == example.spec);
        families.insert(spec.family);
        const auto map = make_shadow_map(spec);
        if constexpr (std::is_same_v<Method, exact_reference>) CHECK(names_exact_reference(spec));
        else CHECK(map->template method_if<Method>() != nullptr);
        ++examples;
    });
    std::set<std::string> registered;
    registered_families::any([&]<class F>() { return registered.insert(std::string(F::name)), false; });
    CHECK(families == registered); // every family gives at least one example
    CHECK(examples >= 2 * registered.size());
}

TEST_CASE("the grammar, the command line's lists and the fuzz dictionary come from the registered families", "[methods][spec][registry]") {
    const std::string grammar = method_grammar();
    const auto tokens = method_spec_tokens();
    const auto has = [&](std::string_view t) { return std::find(tokens.begin(), tokens.end(), t) != tokens.end(); };
    registered_families::any([&]<class F>() {
        CAPTURE(F::name);
        CHECK_THAT(grammar, Catch::Contains(std::string(F::grammar)));
        CHECK(has(F::name));
        for (const auto keyword : F::keywords) CHECK(has(keyword));
        return false;
    });
    CHECK(has("8bit"));
    CHECK_FALSE(has("float")); // the default accumulation, which a spec never names
    CHECK(has("128"));         // occ:128:4's fields
    CHECK_THAT(grammar, Catch::Contains("append :8bit (emulated 8-bit accumulation) to osm, dc, dom, occ, fom or ue"));
    // The command line's default lists: the papers' methods in every one, in the registry's order.
    CHECK(example_spec_list(in_figure) == "osm:16,osm:256,dc:4,dom:3,occ:128:4,fom,msm,avsm,adsm,ue");
    CHECK(example_spec_list(in_animate) == "osm:16,dc:4,dom:3,occ:128:4,fom,msm,avsm,ue");
    for (const auto& spec : example_specs(in_compare)) CHECK_NOTHROW(parse_method_spec(spec));
    const auto compare = test::run_cli("compare --help");
    CHECK_THAT(compare.out + compare.err, Catch::Contains(example_spec_list(in_compare)));
}

TEST_CASE("a spec's accumulation is a parameter: named last, only where the family takes one", "[methods][spec][registry]") {
    CHECK(parse_method_spec("dom:3").accumulation == "float");
    CHECK(parse_method_spec("dom:3:8bit").accumulation == "8bit");
    CHECK(parse_method_spec("osm:16:gamma:8bit").fields == std::vector<std::string>{"16", "gamma"});
    CHECK(make_shadow_map("dc:4:8bit")->method_if<density_clustering<4, emulated_8bit>>() != nullptr);
    CHECK(make_shadow_map("dc:4")->method_if<density_clustering<4, emulated_8bit>>() == nullptr);
    for (const char* bad : {"adsm:8bit", "dsm:8bit", "docc:128:4:8bit", "dom:3:float", "dom:3:8bit:8bit", "dom:8bit:3", "frob:3", "", ":3"}) {
        CAPTURE(bad);
        CHECK_THROWS_AS(parse_method_spec(bad), spec_error);
    }
    CHECK_THROWS_WITH(parse_method_spec("adsm:8bit"), Catch::Contains(":8bit applies to osm, dc, dom, occ, fom or ue"));
    CHECK_THROWS_WITH(parse_method_spec("frob:3"), Catch::Contains("unknown method 'frob'"));
}

TEST_CASE("the exact map through the registry builds streamed, with the buffer build's hash", "[reference][streamed]") {
    const auto m = read_tfx(test::sintel_hair());
    const auto ls = light_space::fit(light_spec::directional({0, -1, -1}), m.bounds(), 128);
    for (const char* spec : {"dsm", "dsm:0.02"}) {
        CAPTURE(spec);
        const auto streamed = make_shadow_map(spec), buffered = make_shadow_map(spec);
        streamed->build(m, ls);
        buffered->build(rasterize(m, ls), ls, {});
        CHECK(streamed->maps_hash() == buffered->maps_hash());
        // A rebuild reuses the workspace (another light first, so that nothing is left over by chance).
        streamed->build(m, light_space::fit(light_spec::point({0.5f, 0.8f, 0.9f}), m.bounds(), 96));
        streamed->build(m, ls);
        CHECK(streamed->maps_hash() == buffered->maps_hash());
        CHECK(streamed->fragment_count() == buffered->fragment_count());
        CHECK(streamed->fragment_count() > 0);
        // Compressed from the model, the exact map is never kept.
        CHECK((streamed->method_if<deep_shadow_map>() == nullptr) == (std::string(spec) != "dsm"));
    }
}

TEST_CASE("a texel has no padding bytes, which maps_hash would read as whatever the build left there", "[methods][registry][determinism]") {
    // adsm's texel was a float beside a bool: three bytes of padding, one of which a build left as it
    // found it, so that adsm's hash depended on the methods built before it in the same process.
    struct bool_beside_float {
        float depth = 0.0f;
        bool any = false;
    };
    STATIC_REQUIRE_FALSE(padding_free<bool_beside_float>);
    STATIC_REQUIRE(padding_free<std::array<float, 3>>);
    // A composition no spec names: an 8-bit measured fibre density's sum beside its 32-bit count.
    STATIC_REQUIRE(padding_free<shadow_method<depth_range<1>, emulated_8bit, fibre_density<fibre_density_source::measured>>::texel_maps>);
    std::size_t examples = 0;
    for_each_example([&](const auto& example) {
        using Method = typename std::decay_t<decltype(example)>::method_type;
        if constexpr (!std::is_same_v<Method, exact_reference>) {
            using texel = typename Method::texel_maps;
            using state = typename Method::placement_type::texel_state;
            STATIC_REQUIRE(padding_free<texel>);
            // The named tail takes only the padding's bytes (no byte more for an empty one).
            constexpr std::size_t parts = (std::is_empty_v<state> ? 0 : sizeof(state)) + sizeof(typename texel::storage_type);
            STATIC_REQUIRE(sizeof(texel) == parts + detail::tail_padding<state, typename texel::storage_type>());
        }
        ++examples;
    });
    CHECK(examples > 0);
}
