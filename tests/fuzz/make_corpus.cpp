// Writes the seed corpus of the fuzz targets into tests/fuzz/corpus/: the model formats through the
// library's own writers, the text formats as small hand-made cases. Run once from the repository root
// after a format changes, and commit the result:
//   g++ -std=c++20 -Iinclude tests/fuzz/make_corpus.cpp -o /tmp/make_corpus && /tmp/make_corpus

#include <hairshadow/io/load.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {
const std::filesystem::path root = "tests/fuzz/corpus";

void text(const std::string& target, const std::string& name, const std::string& content) {
    std::filesystem::create_directories(root / target);
    std::ofstream(root / target / name, std::ios::binary) << content;
}
std::string file(const std::string& target, const std::string& name) {
    std::filesystem::create_directories(root / target);
    return (root / target / name).string();
}
} // namespace

int main() {
    using namespace hairshadow;
    auto small = make_procedural({.style = hair_style::wavy, .strands = 3, .segments = 4});
    auto rich = small;
    rich.thickness.assign(rich.point_count(), 0.001f);
    rich.transparency.assign(rich.point_count(), 0.25f);
    rich.colors.assign(rich.point_count(), glm::vec3(0.5f, 0.4f, 0.3f));
    write_hair(small, file("hair", "plain.hair"));
    write_hair(rich, file("hair", "every_array.hair"));
    write_data(small, file("data", "small.data"));
    auto ragged = small;
    ragged.strand_offsets = {0, 1, 5, 15};
    write_data(ragged, file("data", "ragged.data"));
    write_tfx(small, file("tfx", "tressfx4.tfx"), 4);
    write_tfx(small, file("tfx", "tressfx3.tfx"), 3, 2);

    text("obj", "strands.obj", "# strands\nv 0 0 0\nv 0 1 0\nv 0 2 0.5\nv 1 0 0\nv 1 1 0\nl 1 2 3\nl 4 5\nl -2 -1\n");
    text("obj", "faces.obj",
         "mtllib head.mtl\no head\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ns 1\nusemtl skin\n"
         "f 1/1/1 2/1/1 3/1/1 4/1/1\nf 1//1 3//1 4//1\nf -4 -3 -2\n");
    text("obj", "both.obj", "v 0 0 0 1\nv 0 1 0\nv 1 1 0 0.5 0.5 0.5\ng hair\nl 1/1 2/2 3/3\nf 1 2 3\n");

    text("points", "points.txt", "# x y z\n0 0 0\n\n0.5 -1e-3 2.5e1\n\t1 2 3\r\n");

    const std::vector<std::string> models{"procedural:straight", "procedural:wavy:strands=8:segments=5",
                                          "procedural:curly:strands=4:segments=8:seed=7:amplitude=0.02:wavelength=0.05",
                                          "procedural:clumped:strands=16:clumps=4:length=0.3:radius=0.12"};
    for (std::size_t i = 0; i < models.size(); ++i) text("procedural_spec", "spec" + std::to_string(i), models[i]);

    const std::vector<std::string> lights{"dir:0,-1,-1", "point:0,2,1", "spot:0,1,1:0,-1,-1:30", "dir:1e-3,-1,0"};
    for (std::size_t i = 0; i < lights.size(); ++i) text("light_spec", "light" + std::to_string(i), lights[i]);

    const std::vector<std::string> methods{"osm:16", "osm:8:gamma", "osm:4:uniform:8bit", "dom:3", "dom:4:8bit", "dc:4", "dc:2:8bit",
                                           "occ:128:4", "occ:32:1:8bit", "docc:64:2", "rosm:16", "dsm", "dsm:0.01",
                                           "adsm", "adsm:auto", "adsm:0.4:0.0021:0.35", "avsm:16", "fom:15:sigma", "msm:4:0.5", "ue:4:zero", "avsm", "msm:8:0", "msm:6", "fom:7:8bit"};
    for (std::size_t i = 0; i < methods.size(); ++i) text("method_spec", "method" + std::to_string(i), methods[i]);
}
