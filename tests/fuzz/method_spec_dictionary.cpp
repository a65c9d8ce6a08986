// Prints the method specs' fuzzing dictionary (libFuzzer's -dict format) from the registered families
// (method_spec_tokens): scripts/fuzz.sh writes it for the method_spec target, so that a new method's
// words reach the fuzzer with its registration.
#include <hairshadow/methods/spec.hpp>

#include <cstdio>

int main() {
    for (const auto& token : hairshadow::method_spec_tokens()) std::printf("\"%s\"\n", token.c_str());
    return 0;
}
