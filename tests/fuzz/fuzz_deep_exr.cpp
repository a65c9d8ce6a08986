// Deep OpenEXR reader (io/deep_exr.hpp), from memory through its Imf::IStream: whatever it returns
// must answer queries at every texel with a transmittance in [0, 1] or above only where a sample's
// alpha is negative.
#include "fuzz_support.hpp"

#include <hairshadow/io/deep_exr.hpp>

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        const auto map = hairshadow::parse_deep_exr(fuzz::bytes(data, size), "fuzz.exr");
        const int res = map.resolution();
        FUZZ_EXPECT(res >= 1 && res <= HAIRSHADOW_MAX_RESOLUTION);
        for (int y = 0; y < res; y += 1 + res / 8)
            for (int x = 0; x < res; x += 1 + res / 8)
                for (const auto& s : map.samples(x, y)) {
                    FUZZ_EXPECT(std::isfinite(s.z) && s.z_back >= s.z && s.alpha <= 1.0f);
                    FUZZ_EXPECT(!std::isnan(map.transmittance(x, y, s.z_back)));
                }
        FUZZ_EXPECT(!std::isnan(map.transmittance(glm::vec3(0.0f))));
    });
    return 0;
}
