// The maps of four published methods and their transmittances at a few points, as digests: built
// twice by the tests, header-only and with the kernels compiled once (HAIRSHADOW_SEPARATE_KERNELS,
// hairshadow::kernels), whose outputs must be the same bytes. It includes one method's header at a
// time, as a program that uses separate kernels would. Usage: maps_digest [model.tfx]
#include <hairshadow/io/tfx_format.hpp>
#include <hairshadow/methods/deep_opacity_maps.hpp>
#include <hairshadow/methods/density_clustering.hpp>
#include <hairshadow/methods/occupancy_maps.hpp>
#include <hairshadow/methods/opacity_shadow_maps.hpp>
#include <hairshadow/procedural/generators.hpp>

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {

using namespace hairshadow;

std::uint64_t fnv1a(const void* bytes, std::size_t size, std::uint64_t h) {
    for (std::size_t i = 0; i < size; ++i) h = (h ^ static_cast<const unsigned char*>(bytes)[i]) * 1099511628211ull;
    return h;
}

template <class Method>
void print_digest(const char* name, const hair_model& model, const light_space& light, instruction_set instructions) {
    Method method;
    raster_options options;
    options.instructions = instructions;
    method.build(model, light, options);
    std::uint64_t maps = fnv1a(&method.map_extent(), sizeof(depth_extent), 14695981039346656037ull);
    for (int y = 0; y < light.resolution(); ++y)
        for (int x = 0; x < light.resolution(); ++x) maps = fnv1a(&method.texel(x, y), sizeof(typename Method::texel_maps), maps);
    std::uint64_t queries = 14695981039346656037ull;
    for (std::size_t i = 0; i < model.point_count(); i += model.point_count() / 64 + 1) {
        const float t = method.transmittance(model.points[i]);
        queries = fnv1a(&t, sizeof t, queries);
    }
    std::printf("%-24s maps %016llx  transmittance %016llx\n", name, static_cast<unsigned long long>(maps), static_cast<unsigned long long>(queries));
}

void print_digests(const hair_model& model, int resolution, instruction_set instructions) {
    const light_space light = light_space::fit(light_spec::directional({0.3f, -1.0f, 0.2f}), model.bounds(), resolution);
    print_digest<deep_opacity_maps<3>>("dom:3", model, light, instructions);
    print_digest<opacity_shadow_maps<16>>("osm:16", model, light, instructions);
    print_digest<occupancy_maps<128, 4>>("occ:128:4", model, light, instructions);
    print_digest<density_clustering<4>>("dc:4", model, light, instructions);
}

} // namespace

int main(int argc, char** argv) {
    for (const instruction_set instructions : {instruction_set::scalar, instruction_set::automatic}) {
        std::printf("%s walk\n", instructions == instruction_set::scalar ? "scalar" : "automatic");
        print_digests(make_procedural({.style = hair_style::curly, .strands = 2000, .segments = 16, .seed = 3}), 192, instructions);
        if (argc > 1) print_digests(read_tfx(argv[1]), 256, instructions);
    }
}
