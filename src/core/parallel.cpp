#include "core/parallel.h"
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bmfr {

struct ThreadPool::Impl {
    tbb::task_arena arena;
    explicit Impl(int threads) : arena(threads > 0 ? threads : tbb::info::default_concurrency()) {}
};

ThreadPool::ThreadPool(int threads) : impl_(std::make_unique<Impl>(threads)) {}
ThreadPool::~ThreadPool() = default;

int ThreadPool::currentThreadIndex() {
    return tbb::this_task_arena::current_thread_index();
}

int ThreadPool::threadCount() const {
    return impl_->arena.max_concurrency();
}

void ThreadPool::parallelFor(long count, long grain, const std::function<void(long, long)>& body) {
    if (count <= 0) return;
    impl_->arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<long>(0, count, grain > 0 ? grain : 1),
                          [&](const tbb::blocked_range<long>& r) { body(r.begin(), r.end()); });
    });
}

} // namespace bmfr
