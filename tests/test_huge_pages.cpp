// The allocator of the tiled build's large arrays: huge pages where a block fills them, small pages
// for a block's partly used last one, and no block beyond what a size can say.
#include <hairshadow/core/detail/huge_pages.hpp>

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <string>

#include <unistd.h>

using hairshadow::detail::huge_page_allocator;

namespace {

constexpr std::size_t mib = std::size_t(1) << 20;

/// Whether AddressSanitizer instruments this build: its shadow of a block (a byte for every eight)
/// is memory of its own, which the kernel may back with a huge page too.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool address_sanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool address_sanitizer = true;
#else
constexpr bool address_sanitizer = false;
#endif
#else
constexpr bool address_sanitizer = false;
#endif

/// Resident bytes of this process (/proc/self/statm), or nothing where it cannot be read.
std::optional<std::size_t> resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    std::size_t size = 0, resident = 0;
    if (!(statm >> size >> resident)) return std::nullopt;
    return resident * std::size_t(::sysconf(_SC_PAGESIZE));
}

/// Bytes of this process's memory in transparent huge pages (/proc/self/smaps_rollup), or nothing.
std::optional<std::size_t> huge_page_bytes() {
    std::ifstream rollup("/proc/self/smaps_rollup");
    std::string key;
    std::size_t kib = 0;
    while (rollup >> key) {
        if (key == "AnonHugePages:" && rollup >> kib) return kib * 1024;
        std::getline(rollup, key);
    }
    return std::nullopt;
}

} // namespace

TEST_CASE("huge_page_allocator advises whole huge pages, and a last one only where half of it is used", "[memory]") {
    using alloc = huge_page_allocator<char>;
    CHECK(alloc::huge_pages_advised(2 * mib) == 2 * mib);
    CHECK(alloc::huge_pages_advised(2 * mib + 1) == 2 * mib);
    CHECK(alloc::huge_pages_advised(3 * mib - 1) == 2 * mib);
    CHECK(alloc::huge_pages_advised(3 * mib) == 4 * mib);
    CHECK(alloc::huge_pages_advised(6 * mib + 64 * 1024) == 6 * mib);
}

TEST_CASE("huge_page_allocator: a block holds no more resident memory than it uses", "[memory]") {
    // Three whole huge pages and 64 KiB: advised whole, the last huge page would be resident whole
    // from its first touch (2 MiB for 64 KiB used), as the grouped tile store's 2.3 MiB once held 4.
    huge_page_allocator<char> alloc;
    const std::size_t bytes = 6 * mib + 64 * 1024;
    char* block = alloc.allocate(bytes);
    CHECK(reinterpret_cast<std::uintptr_t>(block) % (2 * mib) == 0);
    const auto resident_before = resident_bytes();
    const auto huge_before = huge_page_bytes();
    std::memset(block, 1, bytes);
    const auto resident_after = resident_bytes();
    const auto huge_after = huge_page_bytes();
    alloc.deallocate(block, bytes);
    if (!resident_before || !resident_after) {
        WARN("no /proc/self/statm: resident memory not checked");
        return;
    }
    // Whatever huge pages the system grants: at most the block, its shadow under AddressSanitizer (a
    // byte for every eight, which memset touches there) and a little for the test's own. Advising
    // the last huge page whole makes it 8 MiB, more than this.
    CHECK(*resident_after - *resident_before <= bytes + bytes / 8 + 512 * 1024);
    // The huge pages the process gained: the block's three. Under AddressSanitizer the shadow's own
    // may add one (8 MiB, seen once in CI at a224e18), so there only the resident check above holds.
    if (huge_before && huge_after && !address_sanitizer) CHECK(*huge_after - *huge_before <= 6 * mib);
}

TEST_CASE("huge_page_allocator refuses blocks beyond the largest object", "[memory][hostile]") {
    huge_page_allocator<std::uint64_t> alloc;
    CHECK_THROWS_AS(alloc.allocate(std::numeric_limits<std::size_t>::max() / 8), std::bad_array_new_length);
    CHECK_THROWS_AS(alloc.allocate(std::size_t(std::numeric_limits<std::ptrdiff_t>::max()) / 8), std::bad_array_new_length);
}
