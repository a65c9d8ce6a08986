// Points files of `hairshadow query`.
#include "fuzz_support.hpp"

#include <hairshadow/io/points_file.hpp>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        for (const auto& p : hairshadow::parse_points(fuzz::bytes(data, size), "fuzz.txt"))
            FUZZ_EXPECT(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    });
    return 0;
}
