// OBJ reader: strands and the triangle mesh.
#include "fuzz_support.hpp"

#include <hairshadow/io/obj_format.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        auto contents = hairshadow::parse_obj(fuzz::bytes(data, size), "fuzz.obj");
        for (const auto& triangle : contents.mesh.triangles)
            for (const auto index : triangle) FUZZ_EXPECT(index < contents.mesh.vertices.size());
        for (const auto& v : contents.mesh.vertices) FUZZ_EXPECT(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        if (contents.hair.strand_count() > 0) fuzz::expect_valid(hairshadow::obj_hair(std::move(contents), "fuzz.obj"));
    });
    return 0;
}
