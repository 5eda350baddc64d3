// Arrays for the big per-primitive data of a build (hundreds of MB for a million triangles):
// 64-byte aligned, and from 4 MiB on placed on 2 MiB boundaries with Linux asked for
// transparent huge pages, so first touching them faults once per 2 MiB instead of per 4 KiB.
// Resizing leaves new elements of trivial types uninitialised, as `new T[n]` would.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tracer {

template <typename T>
struct LargeArrayAllocator {
    using value_type = T;
    static constexpr std::align_val_t kCacheLine{64};
    static constexpr size_t kHugePage = size_t(2) << 20;
    static constexpr size_t kHugeFrom = size_t(4) << 20;

    LargeArrayAllocator() = default;
    template <typename U>
    LargeArrayAllocator(const LargeArrayAllocator<U>&) {}

    T* allocate(size_t n) {
        const size_t bytes = n * sizeof(T);
        if (bytes < kHugeFrom) return static_cast<T*>(::operator new(bytes, kCacheLine));
        const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* memory = std::aligned_alloc(kHugePage, rounded);
        if (!memory) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        madvise(memory, rounded, MADV_HUGEPAGE);  // a hint: without huge pages all still works
#endif
        return static_cast<T*>(memory);
    }
    void deallocate(T* p, size_t n) {
        if (n * sizeof(T) < kHugeFrom)
            ::operator delete(p, kCacheLine);
        else
            std::free(p);
    }
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
    bool operator==(const LargeArrayAllocator&) const {
        return true;
    }
};

template <typename T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace tracer
