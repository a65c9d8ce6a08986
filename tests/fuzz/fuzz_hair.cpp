// Cem Yuksel's .hair reader.
#include "fuzz_support.hpp"

#include <hairshadow/io/hair_format.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] { fuzz::expect_valid(hairshadow::parse_hair(fuzz::bytes(data, size), "fuzz.hair")); });
    return 0;
}
