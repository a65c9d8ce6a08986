// Procedural model specs, and the models they make (kept small, so that a run stays fast).
#include "fuzz_support.hpp"

#include <hairshadow/io/procedural_spec.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::valid_or_error([&] {
        const auto options = hairshadow::parse_procedural_spec(fuzz::text(data, size));
        if (options.strands > 64 || options.segments > 64 || options.clumps > 64) return; // the size limits have their own tests
        fuzz::expect_valid(hairshadow::make_procedural(options));
    });
    return 0;
}
