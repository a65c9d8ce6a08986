#pragma once
// Progress on stderr for long CPU work: what is being done, then how long it took.
#include <chrono>
#include <cstdio>
#include <string>
#include <type_traits>

namespace cli {

inline double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// Runs `work`, announcing `what` first and its time after; returns what `work` returns.
template <class Work>
auto step(const std::string& what, Work&& work) {
    std::fprintf(stderr, "  %-44s", (what + " ...").c_str());
    std::fflush(stderr);
    const auto start = std::chrono::steady_clock::now();
    if constexpr (std::is_void_v<decltype(work())>) {
        work();
        std::fprintf(stderr, "%8.0f ms\n", ms_since(start));
    } else {
        auto result = work();
        std::fprintf(stderr, "%8.0f ms\n", ms_since(start));
        return result;
    }
}

} // namespace cli
