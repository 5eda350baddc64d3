// Arrays for the big per-primitive data of a build (hundreds of MB for a million triangles):
// 64-byte aligned. Resizing leaves new elements of trivial types uninitialised, as `new T[n]`
// would. Not asked onto transparent huge pages (madvise): faulting 2 MiB pages cleared in full
// and compacted for them made whole runs slower than the render time they saved
// (docs/bench/code-figures.md).
#pragma once

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace tracer {

template <typename T>
struct LargeArrayAllocator {
    using value_type = T;
    static constexpr std::align_val_t kCacheLine{64};

    LargeArrayAllocator() = default;
    template <typename U>
    LargeArrayAllocator(const LargeArrayAllocator<U>&) {}

    T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kCacheLine)); }
    void deallocate(T* p, size_t) { ::operator delete(p, kCacheLine); }
    // Elements made without arguments are default-initialised, not zeroed: a large array is
    // filled by its user, often in parallel, and zeroing it first would touch it all twice.
    template <typename U>
    void construct(U* p) {
        ::new (static_cast<void*>(p)) U;
    }
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    bool operator==(const LargeArrayAllocator&) const { return true; }
};

template <typename T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace tracer
