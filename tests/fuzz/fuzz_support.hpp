#pragma once
// What every fuzz target asserts: an input gives a result that passes the library's own checks, or
// throws a hairshadow::error. Anything else (another exception, a failed expectation, a sanitizer
// report) is a defect. The same targets run under libFuzzer (scripts/fuzz.sh) and, in the ordinary
// build, over the committed corpus and reproducers (tests/CMakeLists.txt).

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/hair_model.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

namespace fuzz {

/// Stops the run with a message: libFuzzer records the input as a crash.
[[noreturn]] inline void fail(const char* what) {
    std::fprintf(stderr, "fuzz expectation failed: %s\n", what);
    std::abort();
}

#define FUZZ_EXPECT(condition)                                                                       \
    do {                                                                                             \
        if (!(condition)) ::fuzz::fail(#condition);                                                  \
    } while (0)

/// Runs `body`; a hairshadow::error is an accepted answer, anything else escapes to the fuzzer.
template <class Body>
void valid_or_error(Body&& body) {
    try {
        body();
    } catch (const hairshadow::error&) {
    }
}

/// A model that came back from a reader must pass validate().
inline void expect_valid(const hairshadow::hair_model& model) {
    try {
        hairshadow::validate(model);
    } catch (const hairshadow::model_error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        fail("a reader returned a model that validate() rejects");
    }
}

inline std::span<const unsigned char> bytes(const std::uint8_t* data, std::size_t size) { return {data, size}; }
inline std::string_view text(const std::uint8_t* data, std::size_t size) { return {reinterpret_cast<const char*>(data), size}; }

} // namespace fuzz
