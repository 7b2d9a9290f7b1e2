// An allocator for large per-pixel buffers that starts each one at a different cache line of
// a page. malloc starts every large block at the same offset within a page, and image sizes
// such as 1280x720 and 1920x1080 are whole pages, so without it pixel i of every buffer falls
// in one L1 set, and a store to one buffer stalls loads from the others at the same page offset
// (4K aliasing). Only where a buffer lies moves: no value changes.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>

namespace bmfr {

/// Cache lines and pages, in bytes.
constexpr size_t kCacheLine = 64, kPage = 4096;

/// Floats between planes of `floats` each in one buffer: a whole number of pages and three
/// cache lines, so that up to 21 planes start at different lines of a page.
inline size_t staggeredPlaneFloats(size_t floats) {
    constexpr size_t page = kPage / sizeof(float), lines = 3 * kCacheLine / sizeof(float);
    return (floats + page - 1) / page * page + lines;
}

namespace detail {
/// The line of a page the next large block starts at: successive blocks 37 lines apart.
inline size_t nextStaggerLine() {
    static std::atomic<uint32_t> count{0};
    return size_t(count.fetch_add(1, std::memory_order_relaxed)) * 37 % (kPage / kCacheLine);
}
} // namespace detail

template <class T> struct StaggeredAllocator {
    using value_type = T;
    /// Blocks below this many bytes are allocated as usual.
    static constexpr size_t kMinBytes = size_t(1) << 16;

    StaggeredAllocator() = default;
    template <class U> StaggeredAllocator(const StaggeredAllocator<U>&) {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes < kMinBytes) return static_cast<T*>(::operator new(bytes));
        // The data starts at a cache line past room for the block's address (kept just before
        // it), then a number of lines further.
        char* block = static_cast<char*>(::operator new(bytes + kPage + kCacheLine));
        const uintptr_t first =
            (reinterpret_cast<uintptr_t>(block) + sizeof(void*) + kCacheLine - 1) &
            ~uintptr_t(kCacheLine - 1);
        char* data = reinterpret_cast<char*>(first) + kCacheLine * detail::nextStaggerLine();
        reinterpret_cast<void**>(data)[-1] = block;
        return reinterpret_cast<T*>(data);
    }
    void deallocate(T* p, size_t n) {
        if (n * sizeof(T) < kMinBytes) return ::operator delete(p);
        ::operator delete(reinterpret_cast<void**>(p)[-1]);
    }
    template <class U> bool operator==(const StaggeredAllocator<U>&) const { return true; }
    template <class U> bool operator!=(const StaggeredAllocator<U>&) const { return false; }
};

} // namespace bmfr
