// What a first touch of fresh memory costs on the machine it runs on, on one thread and on two: the
// floor under a cold build, which writes its maps' pages for the first time (BENCHMARKS.md, issue
// 11). Maps MIB MiB advised as huge pages, writes it on THREADS threads, then once more with its pages
// present.
//   build/bench/hairshadow_first_touch [MIB [THREADS...]]     (256, then 1 and 2)
// Run it after some idle seconds and again at once: a virtual machine may have handed its free memory
// back to the host meanwhile, and a first touch then costs far more.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include <sys/mman.h>

int main(int argc, char** argv) {
    const std::size_t mib = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 256;
    std::vector<unsigned> counts;
    for (int i = 2; i < argc; ++i) counts.push_back(unsigned(std::strtoul(argv[i], nullptr, 10)));
    if (counts.empty()) counts = {1, 2};
    if (mib == 0 || mib > (std::size_t(1) << 20)) {
        std::fprintf(stderr, "error: MIB must be 1 to 1048576\n");
        return 2;
    }
    const std::size_t bytes = mib << 20;
    const auto ms_since = [](std::chrono::steady_clock::time_point start) {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    };
    for (const unsigned threads : counts) {
        if (threads == 0 || threads > 256) {
            std::fprintf(stderr, "error: THREADS must be 1 to 256\n");
            return 2;
        }
        void* block = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (block == MAP_FAILED) {
            std::fprintf(stderr, "error: cannot map %zu MiB\n", mib);
            return 1;
        }
        ::madvise(block, bytes, MADV_HUGEPAGE);
        auto* p = static_cast<unsigned char*>(block);
        const std::size_t part = bytes / threads;
        auto start = std::chrono::steady_clock::now();
        std::vector<std::thread> workers;
        for (unsigned t = 0; t < threads; ++t)
            workers.emplace_back([=] { std::memset(p + t * part, 1, t + 1 == threads ? bytes - t * part : part); });
        for (auto& w : workers) w.join();
        const double first = ms_since(start);
        start = std::chrono::steady_clock::now();
        std::memset(p, 2, bytes);
        const double again = ms_since(start);
        std::printf("%zu MiB on %u thread(s): first touch %.1f ms, written again (one thread) %.1f ms\n", mib, threads, first, again);
        ::munmap(block, bytes);
    }
    return 0;
}
