#pragma once
/// @file
/// An allocator for the large arrays of a build (the maps, the prepared segments, the tile stores)
/// that asks Linux for transparent huge pages. A first build touches every page of its maps for the
/// first time, and on a virtual machine a first touch costs about 10 us per 4 KiB page: 64 MiB of
/// maps cost 16,384 faults, and with 2 MiB pages 32.

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace hairshadow::detail {

/// std::allocator, except that blocks of 2 MiB or more are 2 MiB-aligned and advised as huge pages
/// (where the system keeps transparent huge pages for those who ask, as Debian does by default).
template <class T>
struct huge_page_allocator {
    using value_type = T;
    static constexpr std::size_t huge_page = std::size_t(2) << 20;

    huge_page_allocator() noexcept = default;
    template <class U>
    huge_page_allocator(const huge_page_allocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < huge_page) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
        const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
        void* p = std::aligned_alloc(huge_page, rounded);
        if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        ::madvise(p, rounded, MADV_HUGEPAGE); // advice only: where it is refused, small pages serve
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < huge_page) ::operator delete(p, std::align_val_t(alignof(T)));
        else std::free(p);
    }
    template <class U>
    friend bool operator==(const huge_page_allocator&, const huge_page_allocator<U>&) noexcept {
        return true;
    }
};

} // namespace hairshadow::detail
