#include "core/parallel.h"
#include <tbb/info.h>

namespace bmfr {

ThreadPool::ThreadPool(int threads)
    : arena_(std::make_unique<tbb::task_arena>(threads > 0 ? threads
                                                           : tbb::info::default_concurrency())) {}
ThreadPool::~ThreadPool() = default;

tbb::task_arena& ThreadPool::arena() {
    return *arena_;
}
int ThreadPool::threadCount() const {
    return arena_->max_concurrency();
}
int ThreadPool::currentThreadIndex() {
    return tbb::this_task_arena::current_thread_index();
}

} // namespace bmfr
