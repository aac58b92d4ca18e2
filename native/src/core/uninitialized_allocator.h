// An allocator whose resize(n) leaves new elements of trivial types uninitialised, for large
// arrays that are written in full right after (texels of an image being loaded). Zeroing them
// first would fault every page in once for the zeros and stream them again for the values:
// about a fifth of loading an 8192 x 8192 texture (1 GiB of float RGBA), measured with perf.
#pragma once

#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace stratum {

template <typename T>
struct UninitializedAllocator : std::allocator<T> {
    UninitializedAllocator() noexcept = default;
    template <typename U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}

    // Default-initialisation (no zeroing) when no value is given; otherwise as std::allocator.
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (sizeof...(Args) == 0) {
            ::new (static_cast<void*>(p)) U;
        } else {
            ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
        }
    }
};

template <typename T, typename U>
bool operator==(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) noexcept {
    return true;
}

template <typename T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace stratum
