// USC-HairSalon .data reader.
#include "fuzz_support.hpp"

#include <hairshadow/io/data_format.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] { fuzz::expect_valid(hairshadow::parse_data(fuzz::bytes(data, size), "fuzz.data")); });
    return 0;
}
