#pragma once
// The benchmarks' models, loaded once: "sintel" (../shared/data/sintel, 171K segments) and
// "curly1.5M" (procedural:curly:strands=10000:segments=150, 1.5M segments).
#include <hairshadow/hairshadow.hpp>

#include <map>
#include <string>

namespace bench {

inline const hairshadow::hair_model& model(const std::string& name) {
    static std::map<std::string, hairshadow::hair_model> cache;
    auto it = cache.find(name);
    if (it == cache.end()) {
        hairshadow::hair_model m =
            name == "sintel" ? hairshadow::read_tfx(std::string(HAIRSHADOW_SHARED_DIR) + "/data/sintel/sintel_hair.16points.tfx")
                             : hairshadow::make_procedural({.style = hairshadow::hair_style::curly, .strands = 10000, .segments = 150, .seed = 1});
        it = cache.emplace(name, std::move(m)).first;
    }
    return it->second;
}

} // namespace bench
