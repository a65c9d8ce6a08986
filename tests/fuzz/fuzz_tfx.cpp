// TressFX 3 and 4 .tfx reader.
#include "fuzz_support.hpp"

#include <hairshadow/io/tfx_format.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        const auto contents = hairshadow::parse_tfx_file(fuzz::bytes(data, size), "fuzz.tfx");
        fuzz::expect_valid(contents.strands);
        FUZZ_EXPECT(contents.major_version == 3 || contents.major_version == 4);
    });
    return 0;
}
