// std::vector whose resize leaves new elements default-initialised (for numbers and glm
// vectors: not written at all), on 64-byte boundaries like AlignedVector. For lists a kernel
// sizes to an upper bound and then fills through pointers, writing whole SIMD vectors past
// the last element it keeps: value-initialising the bound first would store every byte twice.
#pragma once
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "raster/core/aligned_vector.h"

namespace tessera {

template <class T>
struct ScratchAllocator : CacheAlignedAllocator<T> {
    ScratchAllocator() = default;
    template <class U>
    ScratchAllocator(const ScratchAllocator<U>&) {}
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;  // default-initialisation: no zeroing
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

template <class T>
using ScratchVector = std::vector<T, ScratchAllocator<T>>;

}  // namespace tessera
