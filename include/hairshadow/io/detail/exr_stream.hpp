#pragma once
/// @file
/// OpenEXR plumbing for io/deep_exr.hpp: an Imf::IStream over bytes in memory (so that a file is read
/// once, its size known, and the fuzzer reads without temporary files), and the translation of
/// OpenEXR's Iex exceptions into hairshadow's io_error naming the file. Needs OpenEXR.

#include <hairshadow/core/error.hpp>

#include <ImfIO.h>
#include <Iex.h>

#include <cstdint>
#include <cstring>
#include <new>
#include <span>
#include <string>

namespace hairshadow::detail {

/// An Imf::IStream reading a span of bytes; reading past the end throws Iex::InputExc, as a file would.
class exr_memory_stream final : public Imf::IStream {
public:
    exr_memory_stream(std::span<const unsigned char> bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || std::uint64_t(n) > bytes_.size() - position_) throw Iex::InputExc("unexpected end of file");
        if (n > 0) std::memcpy(c, bytes_.data() + position_, std::size_t(n));
        position_ += std::uint64_t(n);
        return position_ < bytes_.size();
    }
    std::uint64_t tellg() override { return position_; }
    void seekg(std::uint64_t pos) override {
        if (pos > bytes_.size()) throw Iex::InputExc("seek past the end of the file");
        position_ = pos;
    }

private:
    std::span<const unsigned char> bytes_;
    std::uint64_t position_ = 0;
};

/// Runs `body`; hairshadow's errors pass through, anything OpenEXR throws (Iex exceptions, and any
/// other std::exception but running out of memory) becomes an io_error naming `file`.
template <class Body>
decltype(auto) exr_call(const std::string& file, Body&& body) {
    try {
        return body();
    } catch (const error&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw io_error(file, std::string("OpenEXR: ") + e.what());
    }
}

} // namespace hairshadow::detail
