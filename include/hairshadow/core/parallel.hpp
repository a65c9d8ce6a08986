#pragma once
/// @file
/// A minimal fork-join loop on persistent workers. Work items are handed out dynamically, but every
/// kernel writes its result to a place fixed by the item's index, so results never depend on the
/// thread count.

#include <hairshadow/core/detail/thread_pool.hpp>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>

namespace hairshadow {

namespace detail {
/// The hardware threads, asked once: a loop sizes per-thread memory by it, then runs by it.
inline unsigned hardware_threads() noexcept {
    static const unsigned count = std::max(1u, std::thread::hardware_concurrency());
    return count;
}
} // namespace detail

/// Where a parallel loop's workers run, for a program with threads of its own (an engine's job
/// system): by default the library's own pool of persistent threads.
class task_executor {
public:
    virtual ~task_executor() = default;
    /// Calls job(context) at most `workers` times (each call a worker that takes chunks of the loop
    /// until none is left), on whatever threads the executor chooses, at once or one after another,
    /// and returns when every call has returned. A call beyond `workers` returns at once; chunks no
    /// call took run on the calling thread after run returns. `job` does not throw, and run must not
    /// (noexcept: the calls it has queued use the loop's stack). Two threads may call run at once
    /// (two builds), and a job may call it again (a loop inside another's body): an executor whose
    /// run waits for calls that can only start after the calling job returns would deadlock there;
    /// one that runs them on the calling thread when its workers are busy (as the library's pool
    /// does) is safe.
    virtual void run(unsigned workers, void (*job)(void*), void* context) noexcept = 0;
};

/// How the CPU kernels run: `threads` workers (0: every hardware thread), on `executor` when given
/// (it must outlive the call), else on the library's pool. Results never depend on either.
struct execution {
    unsigned threads = 0;
    task_executor* executor = nullptr;
    friend bool operator==(const execution&, const execution&) = default;

    unsigned resolved() const noexcept { return threads != 0 ? threads : detail::hardware_threads(); }
};

/// Threads a loop of `count` items in chunks of `grain` runs on: at most exec.resolved(), the chunk
/// count and four per core (more only cost start-up time). Per-thread scratch memory for
/// parallel_for_slots needs this many slots.
inline unsigned parallel_slots(std::size_t count, const execution& exec, std::size_t grain = 1) noexcept {
    if (count == 0) return 1;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t chunks = (count + grain - 1) / grain;
    const std::size_t useful = 4 * std::size_t(detail::hardware_threads());
    return static_cast<unsigned>(std::max<std::size_t>(1, std::min({std::size_t(exec.resolved()), chunks, useful})));
}

/// Calls body(slot, i) for every i in [0, count) on up to parallel_slots(count, exec, grain)
/// threads, in chunks of `grain`; `slot`, below that count, tells apart the threads running at the
/// same time, for per-thread scratch memory. What a slot runs depends on timing: results must not.
/// The first exception thrown by any call is rethrown after all threads have stopped.
template <class Body>
void parallel_for_slots(std::size_t count, const execution& exec, Body&& body, std::size_t grain = 1) {
    if (count == 0) return;
    grain = std::max<std::size_t>(grain, 1);
    const std::size_t chunks = (count + grain - 1) / grain;
    const unsigned threads = parallel_slots(count, exec, grain);
    if (threads <= 1) {
        for (std::size_t i = 0; i < count; ++i) body(0u, i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::atomic<unsigned> next_slot{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto worker = [&] {
        const unsigned slot = next_slot.fetch_add(1);
        if (slot >= threads) return; // an executor that called more workers than asked
        try {
            for (std::size_t c = next.fetch_add(1); c < chunks; c = next.fetch_add(1)) {
                const std::size_t end = std::min(count, (c + 1) * grain);
                for (std::size_t i = c * grain; i < end; ++i) body(slot, i);
            }
        } catch (...) {
            std::lock_guard lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            next.store(chunks);
        }
    };
    if (exec.executor) {
        exec.executor->run(threads, [](void* context) { (*static_cast<decltype(worker)*>(context))(); }, &worker);
        if (next.load() < chunks) worker(); // fewer calls than workers took every chunk: a slot is left
    } else if (!detail::thread_pool::instance().run(threads, worker)) {
        worker(); // the pool is busy: this thread alone
    }
    if (failure) std::rethrow_exception(failure);
}

/// Calls body(i) for every i in [0, count) on up to exec.resolved() threads, in chunks of `grain`.
/// The first exception thrown by any call is rethrown after all threads have stopped.
template <class Body>
void parallel_for(std::size_t count, const execution& exec, Body&& body, std::size_t grain = 1) {
    parallel_for_slots(count, exec, [&body](unsigned, std::size_t i) { body(i); }, grain);
}

} // namespace hairshadow
