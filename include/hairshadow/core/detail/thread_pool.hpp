#pragma once
/// @file
/// The persistent worker threads behind parallel_for. Starting threads for every parallel loop can
/// cost more than a whole tile pass of a small map; these workers start once, at the first loop that
/// wants them, and sleep between loops.

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <system_error>
#include <thread>

namespace hairshadow::detail {

/// Runs one job at a time on the calling thread plus up to `threads - 1` sleeping workers. A call
/// made while a job runs (a nested loop, or another user thread) is refused, and its caller runs the
/// job alone: that never deadlocks, and results never depend on which threads run a job.
class thread_pool {
public:
    /// The process's pool. It is never destroyed: workers sleep until the process exits, so that no
    /// loop can race the destruction of static objects at exit.
    static thread_pool& instance() {
        static thread_pool* pool = new thread_pool();
        return *pool;
    }

    thread_pool(const thread_pool&) = delete;
    thread_pool& operator=(const thread_pool&) = delete;

    /// Calls job() on this thread and on up to `threads - 1` workers, and returns when every call has
    /// returned. Returns false, having called nothing, when the pool is busy with another job.
    template <class Job>
    bool run(unsigned threads, Job& job) {
        if (threads < 2) return job(), true;
        std::unique_lock lock(mutex_);
        if (busy_) return false;
        busy_ = true;
        grow(threads - 1);
        job_ = [](void* context) { (*static_cast<Job*>(context))(); };
        context_ = &job;
        seats_ = std::min<std::size_t>(threads - 1, workers_);
        ++generation_;
        lock.unlock();
        wake_.notify_all();
        job();
        lock.lock();
        seats_ = 0; // workers that have not woken yet stay asleep
        done_.wait(lock, [&] { return running_ == 0; });
        busy_ = false;
        return true;
    }

    /// Jobs handed to workers so far (tests: a user's executor leaves it unchanged).
    std::size_t jobs_started() {
        std::lock_guard lock(mutex_);
        return generation_;
    }

private:
    thread_pool() = default;

    /// Starts workers up to `count` (under the lock). A refused thread leaves fewer seats; the job's
    /// own loop hands out every item anyway.
    void grow(std::size_t count) {
        while (workers_ < count) {
            try {
                // It has seen every job before the one about to start, which it may join.
                std::thread([this, seen = generation_] { work(seen); }).detach();
            } catch (const std::system_error&) {
                return;
            }
            ++workers_;
        }
    }

    void work(std::size_t seen) {
        std::unique_lock lock(mutex_);
        for (;;) {
            wake_.wait(lock, [&] { return generation_ != seen; });
            seen = generation_;
            if (seats_ == 0) continue;
            --seats_;
            ++running_;
            void (*job)(void*) = job_;
            void* context = context_;
            lock.unlock();
            job(context); // the job catches its own exceptions (parallel_for)
            lock.lock();
            if (--running_ == 0) done_.notify_one();
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_, done_;
    void (*job_)(void*) = nullptr;
    void* context_ = nullptr;
    std::size_t workers_ = 0, generation_ = 0, seats_ = 0, running_ = 0;
    bool busy_ = false;
};

} // namespace hairshadow::detail
