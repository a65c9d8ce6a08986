// The persistent thread pool: nested and concurrent loops, exceptions passed on.
#include "tiled_build_support.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
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

namespace {
/// An engine's job system, as a user would hand it to the library: workers on threads of its own
/// (or, `serial`, one after another on the calling thread), counting what it ran; `extra` calls
/// more workers than asked and `none` none at all, which the loop must survive.
class engine_jobs final : public task_executor {
public:
    enum class mode { threads, serial, extra, none };
    explicit engine_jobs(mode m) : mode_(m) {}
    void run(unsigned workers, void (*job)(void*), void* context) noexcept override {
        ++runs;
        if (mode_ == mode::none) return;
        const unsigned calls = mode_ == mode::extra ? workers + 3 : workers;
        if (mode_ == mode::threads || mode_ == mode::extra) {
            std::vector<std::thread> threads;
            for (unsigned i = 0; i < calls; ++i) threads.emplace_back([&] {
                    ids_of_workers.insert_id();
                    job(context);
                });
            for (auto& t : threads) t.join();
        } else {
            for (unsigned i = 0; i < calls; ++i) job(context);
        }
    }
    std::atomic<int> runs{0};
    struct {
        std::mutex m;
        std::set<std::thread::id> ids;
        void insert_id() {
            std::lock_guard lock(m);
            ids.insert(std::this_thread::get_id());
        }
    } ids_of_workers;

private:
    mode mode_;
};
} // namespace

TEST_CASE("a user's executor runs every parallel task of a build, and the maps are the pool's", "[parallel]") {
    const auto& model = test_model("curly");
    const auto light = light_space::fit(light_spec::directional({0.3f, -1.0f, 0.2f}), model.bounds(), 256);
    deep_opacity_maps<3> pooled;
    pooled.build(model, light, raster_options{.exec = execution{3}});
    for (const auto m : {engine_jobs::mode::threads, engine_jobs::mode::serial, engine_jobs::mode::extra, engine_jobs::mode::none}) {
        CAPTURE(int(m));
        engine_jobs jobs(m);
        const std::size_t pool_jobs = detail::thread_pool::instance().jobs_started();
        std::atomic<std::size_t> items{0};
        std::set<std::thread::id> item_threads;
        std::mutex item_mutex;
        parallel_for(1000, execution{3, &jobs}, [&](std::size_t) {
            ++items;
            std::lock_guard lock(item_mutex);
            item_threads.insert(std::this_thread::get_id());
        });
        CHECK(items == 1000);
        if (m == engine_jobs::mode::threads) { // every item ran on one of the executor's threads
            for (const auto& id : item_threads) CHECK(jobs.ids_of_workers.ids.count(id) == 1);
        }
        deep_opacity_maps<3> own;
        own.build(model, light, raster_options{.exec = execution{3, &jobs}});
        CHECK(jobs.runs > 1);
        CHECK(detail::thread_pool::instance().jobs_started() == pool_jobs); // the library's pool ran nothing
        CHECK(same_maps(own, pooled));
    }
}

TEST_CASE("two threads building two maps at once build the maps each builds alone", "[parallel]") {
    const auto& model = test_model("curly");
    const auto key = light_space::fit(light_spec::directional({0.3f, -1.0f, 0.2f}), model.bounds(), 256);
    const auto fill = light_space::fit(light_spec::point(model.bounds().center() + glm::vec3(0.0f, 2.0f * model.bounds().diagonal(), 0.0f)), model.bounds(), 192);
    deep_opacity_maps<3> key_alone, key_together;
    occupancy_maps<128, 4> fill_alone, fill_together;
    key_alone.build(model, key);
    fill_alone.build(model, fill);
    for (int round = 0; round < 3; ++round) { // the pool busy with one build, the other runs on its own thread
        std::thread other([&] { fill_together.build(model, fill, raster_options{.exec = execution{2}}); });
        key_together.build(model, key, raster_options{.exec = execution{2}});
        other.join();
        CHECK(same_maps(key_together, key_alone));
        CHECK(same_maps(fill_together, fill_alone));
    }
}
