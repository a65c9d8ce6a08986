#pragma once
/// @file
/// A walk over an OpenEXR header's bytes before OpenEXR reads it (io/deep_exr.hpp): OpenEXR 3.1
/// allocates a string attribute's declared size before reading it (a few bytes of a hostile file
/// then ask for gigabytes), and reads some types by their own layout whatever size they declare.
/// The walk follows OpenEXR's reading: a channel list up to its empty name, fixed-size types only at
/// their size, a preview at 8 + 4 w h bytes, anything else at its declared size; every size must fit
/// in the bytes left. Then, for a deep scanline image, the chunks: OpenEXR 3.1 also allocates a
/// chunk's declared sizes before reading it (readPixelData), so every chunk the offset table names
/// must lie inside the file with sizes that fit in it (check_deep_chunks). Needs no OpenEXR.

#include <hairshadow/core/error.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

namespace hairshadow::detail {

class exr_header_walk {
public:
    exr_header_walk(std::span<const unsigned char> bytes, const std::string& file) : b_(bytes), file_(file) {}

    /// Walks the header; returns its version field. Refuses multi-part files (a map is one part).
    /// Afterwards end() is the first byte after the header (a single-part image's offset table).
    int run() {
        if (b_.size() < 8) fail("too short for an OpenEXR header");
        const int version = int(u32(4));
        if (version & 0x1000) fail("a multi-part OpenEXR file; only single-part deep scanline images are read");
        at_ = 8;
        for (;;) {
            need(1);
            if (b_[at_] == 0) return ++at_, version;
            name();
            const std::string_view type = name();
            need(4);
            const std::uint32_t size = u32(at_);
            at_ += 4;
            value(type, size);
        }
    }

    std::size_t end() const noexcept { return at_; }

private:
    [[noreturn]] void fail(const std::string& why) const { throw io_error(file_, why); }
    void need(std::uint64_t n) const {
        if (n > b_.size() - at_) fail("the header runs past the end of the file");
    }
    std::uint32_t u32(std::size_t at) const {
        return std::uint32_t(b_[at]) | std::uint32_t(b_[at + 1]) << 8 | std::uint32_t(b_[at + 2]) << 16 | std::uint32_t(b_[at + 3]) << 24;
    }
    std::string_view name() {
        const auto first = b_.begin() + std::ptrdiff_t(at_);
        const auto last = first + std::ptrdiff_t(std::min<std::size_t>(256, b_.size() - at_)); // never past the end of the bytes
        const auto end = std::find(first, last, 0);
        if (end == last) fail("an attribute name in the header is not terminated");
        at_ = std::size_t(end - b_.begin()) + 1;
        return {reinterpret_cast<const char*>(&*first), std::size_t(end - first)};
    }
    static std::uint32_t fixed_size(std::string_view type) {
        constexpr std::pair<std::string_view, std::uint32_t> sizes[] = {
            {"int", 4}, {"float", 4}, {"double", 8}, {"box2i", 16}, {"box2f", 16}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12},
            {"v3d", 24}, {"m33f", 36}, {"m44f", 64}, {"m33d", 72}, {"m44d", 128}, {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},
            {"deepImageState", 1}, {"chromaticities", 32}, {"rational", 8}, {"timecode", 8}, {"keycode", 28}, {"tiledesc", 9}};
        for (const auto& [name, size] : sizes)
            if (name == type) return size;
        return 0;
    }
    void value(std::string_view type, std::uint32_t size) {
        if (type == "chlist") { // entries (name, 16 bytes) up to an empty name, as OpenEXR reads them
            for (;;) {
                need(1);
                if (b_[at_] == 0) return void(++at_);
                name();
                need(16);
                at_ += 16;
            }
        }
        need(size);
        if (const auto fixed = fixed_size(type); fixed && size != fixed) fail("a '" + std::string(type) + "' attribute of " + std::to_string(size) + " bytes");
        if (type == "preview") { // width x height RGBA bytes after the two sizes: no product that can wrap
            const std::uint64_t w = size < 8 ? 0 : u32(at_), h = size < 8 ? 0 : u32(at_ + 4);
            if (size < 8 || (w != 0 && h > (size - 8) / 4 / w) || w * h * 4 + 8 != size) fail("a preview image of the wrong size");
        }
        at_ += size;
    }

    std::span<const unsigned char> b_;
    const std::string& file_;
    std::size_t at_ = 0;
};

/// Checks a single-part deep scanline image's chunks before OpenEXR reads them: `chunks` offsets
/// (little-endian 64-bit) at `table`, each pointing inside the file at a chunk of 28 bytes (its first
/// scanline, the packed sizes of its sample count table and of its data, the unpacked size of its
/// data) followed by the two packed parts, which must fit in the file; the unpacked size at most
/// `expansion` times the packed one (the compression's bound). OpenEXR 3.1 seeks only to the first
/// chunk it reads and reads the others back to back from there (readPixelData), so each chunk must
/// start where the one read before it ends: in increasing order where `increasing` (INCREASING_Y),
/// else decreasing, as OpenEXR writes and reads them; otherwise the chunks checked would not be the
/// ones read. A chunk the table does not place (an incomplete file, whose offsets OpenEXR would
/// rebuild by scanning) is refused too.
inline void check_deep_chunks(std::span<const unsigned char> b, std::size_t table, std::uint64_t chunks, double expansion, bool increasing,
                              const std::string& file) {
    const auto u64 = [&](std::uint64_t at) {
        std::uint64_t v = 0;
        for (int i = 7; i >= 0; --i) v = v << 8 | b[std::size_t(at) + std::size_t(i)];
        return v;
    };
    const std::uint64_t size = b.size();
    if (table > size || chunks > (size - table) / 8) throw io_error(file, "the chunk offset table runs past the end of the file");
    const std::uint64_t first = table + 8 * chunks;
    std::uint64_t end_of_last = 0; // where the chunk read before this one ends
    for (std::uint64_t k = 0; k < chunks; ++k) {
        const std::uint64_t i = increasing ? k : chunks - 1 - k;
        const std::uint64_t at = u64(table + 8 * i);
        if (at < first || at > size || size - at < 28) throw io_error(file, "chunk " + std::to_string(i) + "'s offset points outside the file");
        if (k > 0 && at != end_of_last)
            throw io_error(file, "chunk " + std::to_string(i) + " does not start where the chunk read before it ends (OpenEXR reads them back to back)");
        const std::uint64_t counts = u64(at + 4), packed = u64(at + 12), unpacked = u64(at + 20);
        const std::uint64_t left = size - at - 28;
        if (counts > left || packed > left - counts)
            throw io_error(file, "chunk " + std::to_string(i) + " declares " + std::to_string(counts) + " + " + std::to_string(packed) +
                                     " bytes; the file has " + std::to_string(left) + " after it");
        if (double(unpacked) > expansion * double(packed) + 64.0)
            throw io_error(file, "chunk " + std::to_string(i) + " claims " + std::to_string(unpacked) + " bytes unpacked from " + std::to_string(packed));
        end_of_last = at + 28 + counts + packed;
    }
}

} // namespace hairshadow::detail
