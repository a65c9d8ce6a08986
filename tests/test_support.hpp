#pragma once
// Helpers shared by the tests: paths, temporary files, running the command line.

#include <hairshadow/hairshadow.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace test {

/// ../shared beside the checkout (set by CMake).
inline std::string shared_dir() { return HAIRSHADOW_SHARED_DIR; }
inline std::string sintel_hair() { return shared_dir() + "/data/sintel/sintel_hair.16points.tfx"; }
inline std::string sintel_head() { return shared_dir() + "/data/sintel/sintel_head.obj"; }

/// A fresh directory for one test's files, removed at the end of the test; the process id in its
/// name keeps two runs of the suite at once (ctest -j, a sanitizer build beside a plain one) apart.
class temp_dir {
public:
    explicit temp_dir(const std::string& name)
        : path_(std::filesystem::temp_directory_path() / ("hairshadow_test_" + name + "_" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~temp_dir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

inline void write_bytes(const std::string& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}
inline void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}
inline std::vector<unsigned char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}
template <class T>
void append(std::vector<unsigned char>& bytes, const T& value) {
    const auto* p = reinterpret_cast<const unsigned char*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
}

/// Result of running a command: exit status, stdout and stderr.
struct run_result {
    int status;
    std::string out;
    std::string err;
};

/// Runs the hairshadow command with `args` (shell words), capturing both streams.
inline run_result run_cli(const std::string& args) {
    const auto dir = std::filesystem::temp_directory_path();
    static int counter = 0;
    const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const auto err_path = (dir / ("hairshadow_cli_err_" + tag)).string();
    const std::string command = std::string(HAIRSHADOW_CLI) + " " + args + " 2>" + err_path;
    run_result result{-1, {}, {}};
    if (FILE* pipe = popen(command.c_str(), "r")) {
        std::array<char, 4096> buf;
        std::size_t n;
        while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) result.out.append(buf.data(), n);
        const int raw = pclose(pipe);
        result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    }
    std::ifstream err(err_path);
    result.err.assign(std::istreambuf_iterator<char>(err), {});
    std::filesystem::remove(err_path);
    return result;
}

/// A small model: `strands` straight strands of `points` points each.
inline hairshadow::hair_model grid_model(int strands, int points) {
    hairshadow::hair_model m;
    for (int s = 0; s < strands; ++s) {
        std::vector<glm::vec3> pts;
        for (int i = 0; i < points; ++i) pts.emplace_back(float(s) * 0.1f, -float(i) * 0.05f, float(s % 3) * 0.02f);
        m.add_strand(pts);
    }
    m.default_thickness = 0.001f;
    return m;
}

/// Whether `method` builds the same maps tile by tile from `model` as from `fragments` (rasterised
/// from it for `light`) on one thread and on three, and covers more than 1,000 texels.
template <class Method>
bool same_maps_tiled_and_buffered(Method method, const hairshadow::hair_model& model, const hairshadow::fragment_buffer& fragments,
                                  const hairshadow::light_space& light) {
    auto tiled = method, one = method, three = method;
    tiled.build(model, light);
    one.build(fragments, light, tiled.map_extent(), hairshadow::execution{1});
    three.build(fragments, light, tiled.map_extent(), hairshadow::execution{3});
    std::size_t covered = 0;
    for (int y = 0; y < light.resolution(); ++y)
        for (int x = 0; x < light.resolution(); ++x) {
            if (!(tiled.texel(x, y) == one.texel(x, y)) || !(one.texel(x, y) == three.texel(x, y))) return false;
            covered += !fragments.texel(x, y).empty();
        }
    return covered > 1000;
}

/// Whether `map` (the registry's, built from `model`) gives `direct`'s (the template's, built the
/// same) transmittance at every point of `model`, bit for bit, with a quarter of them shadowed.
template <class Map, class Method>
bool same_transmittance(const Map& map, const Method& direct, const hairshadow::hair_model& model) {
    std::size_t shadowed = 0;
    for (const auto& p : model.points) {
        const float t = direct.transmittance(p);
        if (map.transmittance(p) != t) return false;
        shadowed += t < 0.9f;
    }
    return shadowed > model.points.size() / 4;
}

} // namespace test
