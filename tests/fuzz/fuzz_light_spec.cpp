// Light specs: parsed, fitted to a small model and used for a build; every transmittance must be a
// number in [0, 1].
#include "fuzz_support.hpp"

#include <hairshadow/methods/published.hpp>
#include <hairshadow/procedural/generators.hpp>

#include <cmath>

namespace {
const hairshadow::hair_model& model() {
    static const hairshadow::hair_model m = hairshadow::make_procedural({.strands = 40, .segments = 6});
    return m;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        const auto spec = hairshadow::parse_light_spec(fuzz::text(data, size));
        const auto light = hairshadow::light_space::fit(spec, model().bounds(), 32);
        hairshadow::deep_opacity_maps<3> map; // a method known at compile time: no registry to compile
        map.build(model(), light, {.exec = {1}});
        std::vector<float> t(model().point_count());
        map.transmittance(model().points, t, {}, {1});
        for (const float v : t) FUZZ_EXPECT(v >= 0.0f && v <= 1.0f);
    });
    return 0;
}
