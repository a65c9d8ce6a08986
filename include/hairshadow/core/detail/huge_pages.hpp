#pragma once
/// @file
/// An allocator for the large arrays of a build (the maps, the prepared segments, the tile stores)
/// that asks Linux for transparent huge pages. A first build touches every page of its maps for the
/// first time, and each first touch is a page fault, costly on a virtual machine most of all: 64 MiB of
/// maps are 16,384 faults in 4 KiB pages and 32 in 2 MiB ones.

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <new>
#include <type_traits>
#include <utility>

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
        // No block beyond the largest object, its rounding included (which could otherwise wrap).
        if (n > (std::size_t(std::numeric_limits<std::ptrdiff_t>::max()) - huge_page) / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < huge_page) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
        const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
        void* p = std::aligned_alloc(huge_page, rounded);
        if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE) && defined(MADV_NOHUGEPAGE)
        // Advice only: where it is refused, small pages serve. A huge page is resident whole from its
        // first touch, so the last one, partly used, is advised only where the block fills at least half
        // of it; otherwise it is kept to small pages (even where the system gives huge pages to all):
        // advised whole, an array of 2.3 MiB would hold 4 MiB (BENCHMARKS.md, "Full rebuilds", the
        // entry on huge pages only where filled).
        const std::size_t advised = huge_pages_advised(bytes);
        ::madvise(p, advised, MADV_HUGEPAGE);
        if (advised < rounded) ::madvise(static_cast<char*>(p) + advised, rounded - advised, MADV_NOHUGEPAGE);
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < huge_page) ::operator delete(p, std::align_val_t(alignof(T)));
        else std::free(p);
    }
    /// Bytes of a block of `bytes` (2 MiB or more) advised as huge pages: its whole huge pages, and the
    /// last, partly filled one where at least half of it is used.
    static constexpr std::size_t huge_pages_advised(std::size_t bytes) noexcept { return (bytes + huge_page / 2) / huge_page * huge_page; }
    template <class U>
    friend bool operator==(const huge_page_allocator&, const huge_page_allocator<U>&) noexcept {
        return true;
    }
};

/// huge_page_allocator for an array whose owner initialises the elements that growing it adds: the
/// maps, zeroed in parallel by the build's threads. Growing it (vector::resize) leaves the new
/// elements as allocated, so that their pages are first touched by those threads, not cleared first
/// on one: a first touch of fresh memory is slow (slower still on a virtual machine whose host has
/// taken its free memory back), and the threads share that cost (BENCHMARKS.md, "Density clustering
/// walks in any order; the maps cleared by the build's threads"). Only for trivially copyable types,
/// whose bytes the owner may write.
template <class T>
struct overwritten_huge_page_allocator : huge_page_allocator<T> {
    template <class U>
    struct rebind {
        using other = overwritten_huge_page_allocator<U>;
    };
    overwritten_huge_page_allocator() noexcept = default;
    template <class U>
    overwritten_huge_page_allocator(const overwritten_huge_page_allocator<U>&) noexcept {}

    /// Value-initialisation: no stores; the owner initialises the element before reading it. Starting
    /// the lifetime of an array of bytes there creates the element implicitly (C++20 [intro.object]):
    /// storage reused after a shrink holds an object again.
    template <class U>
    void construct(U* p) noexcept {
        static_assert(std::is_trivially_copyable_v<U>, "an element left as allocated must be trivially copyable: its owner writes its bytes");
        ::new (static_cast<void*>(p)) unsigned char[sizeof(U)];
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

} // namespace hairshadow::detail
