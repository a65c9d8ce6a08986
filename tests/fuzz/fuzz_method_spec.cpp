// Method specs: parsed, made and built on a small model at a small resolution; every transmittance
// must be a number in [0, 1].
#include "fuzz_support.hpp"

#include <hairshadow/methods/registry.hpp>
#include <hairshadow/procedural/generators.hpp>

namespace {
const hairshadow::hair_model& model() {
    static const hairshadow::hair_model m = hairshadow::make_procedural({.strands = 40, .segments = 6});
    return m;
}
const hairshadow::light_space& light() {
    static const hairshadow::light_space l = hairshadow::light_space::fit(hairshadow::light_spec::directional({0, -1, -1}), model().bounds(), 16);
    return l;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        auto map = hairshadow::make_shadow_map(fuzz::text(data, size));
        map->build(model(), light(), {.exec = {1}});
        std::vector<float> t(model().point_count());
        map->transmittance(model().points, t, {}, {1});
        for (const float v : t) FUZZ_EXPECT(v >= 0.0f && v <= 1.0f);
    });
    return 0;
}
