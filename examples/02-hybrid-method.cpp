// 02-hybrid-method: composing a shadow method that no paper describes from hairshadow's policies:
// deep opacity maps' per-texel layers (Yuksel & Keyser 2008) read through occupancy bits and slabs
// (Sintorn & Assarsson 2009), beside the two published methods it mixes, all measured against the
// exact deep shadow map (Lokovic & Veach 2000) on a procedural wavy model. Prints a table.
#include <hairshadow/hairshadow.hpp>

#include <cstdio>

using namespace hairshadow;

// The hybrid: 64 equal slices from each texel's first fragment, stretched to its last, 2 slabs.
using deep_occupancy = shadow_method<per_pixel_depth<64, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation,
                                     occupancy_bitcount<2>>;

template <class Method>
void report(const char* name, const hair_model& model, const fragment_buffer& fragments, const light_space& light,
            const std::vector<float>& exact) {
    Method method;
    method.build(fragments, light);
    std::vector<float> t(model.point_count());
    method.transmittance(model.points, t);
    double sum = 0;
    for (std::size_t i = 0; i < t.size(); ++i) sum += std::abs(t[i] - exact[i]);
    std::printf("%-22s %8.2f MiB   mean |T - T_exact| %.4f\n", name, double(method.memory_bytes()) / 1048576.0, sum / double(t.size()));
}

int main() {
    const hair_model model = make_procedural({.style = hair_style::wavy, .strands = 3000, .segments = 24, .seed = 2});
    const light_space light = light_space::fit(light_spec::directional({1, -1, 0}), model.bounds(), 256);
    const fragment_buffer fragments = rasterize(model, light);
    const deep_shadow_map reference(fragments, light);
    std::vector<float> exact(model.point_count());
    reference.transmittance(model.points, exact);
    report<deep_opacity_maps<3>>("deep opacity maps 3", model, fragments, light, exact);
    report<occupancy_maps<64, 2>>("occupancy maps 64/2", model, fragments, light, exact);
    report<deep_occupancy>("hybrid 64/2", model, fragments, light, exact);
}
