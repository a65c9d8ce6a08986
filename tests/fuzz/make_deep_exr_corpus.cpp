// Writes the seed corpus of the deep OpenEXR fuzz target into tests/fuzz/corpus/deep_exr/: small exact
// and compressed maps through write_deep_exr. Run once from the repository root after the format
// changes, and commit the result:
//   g++ -std=c++20 -Iinclude -isystem /usr/include/OpenEXR -isystem /usr/include/Imath tests/fuzz/make_deep_exr_corpus.cpp \
//       -o /tmp/make_deep_exr_corpus -lOpenEXR-3_1 -lIex-3_1 && /tmp/make_deep_exr_corpus

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/deep_exr.hpp>

#include <filesystem>

int main() {
    using namespace hairshadow;
    const std::filesystem::path dir = "tests/fuzz/corpus/deep_exr";
    std::filesystem::create_directories(dir);
    const auto model = make_procedural({.style = hair_style::wavy, .strands = 6, .segments = 4});
    for (int res : {2, 4}) {
        const auto light = light_space::fit(light_spec::directional({0, -1, -1}), model.bounds(), res);
        const deep_shadow_map exact(rasterize(model, light), light);
        write_deep_exr((dir / ("exact" + std::to_string(res) + ".exr")).string(), exact);
        write_deep_exr((dir / ("compressed" + std::to_string(res) + ".exr")).string(), compressed_deep_shadow_map(exact, 0.001f));
    }
}
