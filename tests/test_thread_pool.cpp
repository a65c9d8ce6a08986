// The persistent thread pool: nested and concurrent loops, exceptions passed on.
#include "tiled_build_support.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <numeric>
#include <random>
#include <set>
#include <thread>
#include <tuple>

using namespace hairshadow;
using namespace test;

TEST_CASE("the thread pool runs nested and concurrent loops and passes exceptions on", "[parallel]") {
    std::vector<int> hits(1000, 0);
    parallel_for(10, execution{4}, [&](std::size_t i) {
        parallel_for(100, execution{4}, [&](std::size_t j) { ++hits[i * 100 + j]; }); // nested: runs on the calling thread
    });
    CHECK(std::count(hits.begin(), hits.end(), 1) == 1000);

    std::atomic<int> total{0};
    std::thread other([&] { parallel_for(5000, execution{3}, [&](std::size_t) { ++total; }); });
    parallel_for(5000, execution{3}, [&](std::size_t) { ++total; });
    other.join();
    CHECK(total == 10000);

    CHECK_THROWS_AS(parallel_for(100, execution{4}, [](std::size_t i) {
                        if (i == 57) throw argument_error("item 57");
                    }),
                    argument_error);
    // The pool still works after a failed loop.
    std::atomic<int> after{0};
    parallel_for(64, execution{8}, [&](std::size_t) { ++after; });
    CHECK(after == 64);
    // Slots tell the threads of one loop apart.
    std::vector<std::atomic<int>> in_use(parallel_slots(1000, execution{3}));
    std::atomic<bool> shared{false};
    parallel_for_slots(1000, execution{3}, [&](unsigned slot, std::size_t) {
        if (in_use[slot].fetch_add(1) != 0) shared = true;
        in_use[slot].fetch_sub(1);
    });
    CHECK_FALSE(shared);
}
