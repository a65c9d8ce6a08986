#pragma once
/// @file
/// A minimal fork-join loop. Work items are handed out dynamically, but every kernel writes its result
/// to a place fixed by the item's index, so results never depend on the thread count.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace hairshadow {

/// Thread count for the CPU kernels: 0 means every hardware thread.
struct execution {
    unsigned threads = 0;

    unsigned resolved() const noexcept {
        if (threads != 0) return threads;
        const unsigned hw = std::thread::hardware_concurrency();
        return hw == 0 ? 1u : hw;
    }
};

/// Calls body(i) for every i in [0, count) on up to exec.resolved() threads, in chunks of `grain`.
/// The first exception thrown by any call is rethrown after all threads have stopped.
template <class Body>
void parallel_for(std::size_t count, const execution& exec, Body&& body, std::size_t grain = 1) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t chunks = (count + grain - 1) / grain;
    // More threads than items, or than a few per core, only cost start-up time.
    const std::size_t useful = std::max<std::size_t>(4 * std::max(1u, std::thread::hardware_concurrency()), 1);
    const unsigned threads = static_cast<unsigned>(std::min({std::size_t(exec.resolved()), chunks, useful}));
    if (threads <= 1) {
        for (std::size_t i = 0; i < count; ++i) body(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto worker = [&] {
        try {
            for (std::size_t c = next.fetch_add(1); c < chunks; c = next.fetch_add(1)) {
                const std::size_t end = std::min(count, (c + 1) * grain);
                for (std::size_t i = c * grain; i < end; ++i) body(i);
            }
        } catch (...) {
            std::lock_guard lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            next.store(chunks);
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    try {
        for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    } catch (const std::system_error&) {
        // The system refused another thread: the ones started (and this one) drain every chunk anyway.
    }
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

} // namespace hairshadow
