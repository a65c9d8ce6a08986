// The same program as single_header_user.cpp, including only what it uses: the TressFX reader and
// one method's header.
#include <hairshadow/io/tfx_format.hpp>
#include <hairshadow/methods/deep_opacity_maps.hpp>

#include <cstdio>

int main(int argc, char** argv) {
    using namespace hairshadow;
    if (argc < 2) return 2;
    const hair_model model = read_tfx(argv[1]);
    const light_space light = light_space::fit(light_spec::directional({0, -1, 0}), model.bounds(), 512);
    deep_opacity_maps<3> maps;
    maps.build(model, light);
    std::printf("T = %.6f\n", double(maps.transmittance(model.points[model.point_count() / 2])));
}
