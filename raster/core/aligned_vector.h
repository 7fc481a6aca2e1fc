// std::vector whose storage starts on a 64-byte boundary (one cache line, one AVX-512
// register), so SIMD kernels may use aligned loads and stores on it.
#pragma once
#include <cstddef>
#include <new>
#include <vector>

namespace tessera {

template <class T>
struct CacheAlignedAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlignment{64};
    CacheAlignedAllocator() = default;
    template <class U>
    CacheAlignedAllocator(const CacheAlignedAllocator<U>&) {}
    T* allocate(size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
    void deallocate(T* p, size_t) { ::operator delete(p, kAlignment); }
    template <class U>
    bool operator==(const CacheAlignedAllocator<U>&) const { return true; }
};

template <class T>
using AlignedVector = std::vector<T, CacheAlignedAllocator<T>>;

}  // namespace tessera
