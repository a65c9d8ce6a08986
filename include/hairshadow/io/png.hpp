#pragma once
/// @file
/// PNG and animated PNG (APNG) output through stb_image_write (Debian's libstb-dev, `<stb/stb_image_write.h>`), compiled into
/// each including translation unit as static functions so that no link step is needed.

#include <hairshadow/core/error.hpp>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#ifndef STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define HAIRSHADOW_STB_DEFINED_HERE
#endif
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#ifdef HAIRSHADOW_STB_DEFINED_HERE
#undef STB_IMAGE_WRITE_STATIC
#undef STB_IMAGE_WRITE_IMPLEMENTATION
#undef HAIRSHADOW_STB_DEFINED_HERE
#endif

namespace hairshadow {

namespace detail {
/// stb's encoder counts the filtered image's bytes, (width x channels + 1) x height, in an int.
inline void check_png_size(int width, int height, int channels) {
    if ((std::size_t(width) * std::size_t(channels) + 1) * std::size_t(height) > std::size_t(std::numeric_limits<int>::max()))
        throw argument_error("PNG: " + std::to_string(width) + "x" + std::to_string(height) + " pixels are more than one image may hold here (2 GiB)");
}
} // namespace detail

/// Writes 8-bit pixels (row-major, top row first, `channels` of 1, 3 or 4) as a PNG.
inline void write_png(const std::string& path, int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
        pixels.size() != std::size_t(width) * std::size_t(height) * std::size_t(channels))
        throw argument_error("write_png: pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height));
    detail::check_png_size(width, height, channels);
    if (!stbi_write_png(path.c_str(), width, height, channels, pixels.data(), width * channels))
        throw io_error(path, "cannot write PNG");
}

namespace detail {
/// CRC-32 of PNG chunks (ISO 3309, as the PNG specification's section 5.5 gives it).
inline std::uint32_t png_crc(std::uint32_t crc, const std::uint8_t* data, std::size_t size) noexcept {
    static const auto table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    crc = ~crc;
    for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}
inline void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift : {24, 16, 8, 0}) out.push_back(std::uint8_t(v >> shift));
}
inline std::uint32_t get_u32(const std::uint8_t* p) noexcept {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}
} // namespace detail

/// Writes an animated PNG (APNG 1.0: acTL, then an fcTL per frame, the first frame's image data in IDAT
/// so that a viewer without APNG shows it, the others in fdAT), frame by frame as they are made, so a
/// long animation is never held whole. Every frame covers the whole image; the animation loops.
class apng_writer {
public:
    /// Opens `path` for `frame_count` frames of width x height pixels with `channels` (3 or 4), each
    /// shown for delay_numerator / delay_denominator seconds (1/fps: 1, fps). Throws argument_error for
    /// sizes PNG cannot hold or a zero denominator, before touching the file; io_error if it cannot write.
    apng_writer(const std::string& path, int width, int height, int channels, int frame_count, std::uint16_t delay_numerator,
                std::uint16_t delay_denominator)
        : path_(path), width_(width), height_(height), channels_(channels), frames_(frame_count), delay_numerator_(delay_numerator),
          delay_denominator_(delay_denominator) {
        if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) || frame_count <= 0 || delay_denominator == 0)
            throw argument_error("apng_writer: needs a positive size and frame count, 3 or 4 channels and a non-zero delay denominator");
        detail::check_png_size(width, height, channels);
        out_.open(path, std::ios::binary);
        if (!out_) throw io_error(path, "cannot write");
        static constexpr std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
        out_.write(reinterpret_cast<const char*>(signature), sizeof signature);
    }

    /// Adds the next frame: 8-bit pixels, row-major, top row first.
    void add_frame(const std::vector<std::uint8_t>& pixels) {
        if (written_ == frames_) throw argument_error("apng_writer: more frames than the " + std::to_string(frames_) + " announced");
        if (pixels.size() != std::size_t(width_) * std::size_t(height_) * std::size_t(channels_))
            throw argument_error("apng_writer: a frame does not match " + std::to_string(width_) + "x" + std::to_string(height_));
        int size = 0;
        unsigned char* png = stbi_write_png_to_mem(pixels.data(), width_ * channels_, width_, height_, channels_, &size);
        if (!png) throw io_error(path_, "cannot encode a frame");
        const std::vector<std::uint8_t> encoded(png, png + size);
#ifdef STBIW_FREE
        STBIW_FREE(png); // the user's allocator, where they gave stb one
#else
        std::free(png);
#endif
        // stb's PNG: the signature, then chunks (length, type, data, CRC); keep IHDR once and the image data.
        std::vector<std::uint8_t> chunk;
        for (std::size_t at = 8; at + 12 <= encoded.size();) {
            const std::uint32_t length = detail::get_u32(&encoded[at]);
            if (length > encoded.size() - at - 12) throw io_error(path_, "stb wrote a chunk past its PNG's end");
            const std::string_view type(reinterpret_cast<const char*>(&encoded[at + 4]), 4);
            const std::uint8_t* data = &encoded[at + 8];
            if (type == "IHDR" && written_ == 0) {
                write_chunk("IHDR", data, length);
                chunk.clear();
                detail::put_u32(chunk, std::uint32_t(frames_));
                detail::put_u32(chunk, 0); // loop for ever
                write_chunk("acTL", chunk.data(), chunk.size());
            } else if (type == "IDAT") {
                if (!frame_control_written_) write_frame_control();
                if (written_ == 0) write_chunk("IDAT", data, length);
                else {
                    chunk.clear();
                    detail::put_u32(chunk, sequence_++);
                    chunk.insert(chunk.end(), data, data + length);
                    write_chunk("fdAT", chunk.data(), chunk.size());
                }
            }
            at += 12 + length;
        }
        frame_control_written_ = false;
        if (++written_ == frames_) write_chunk("IEND", nullptr, 0);
        if (!out_) throw io_error(path_, "cannot write");
    }

    /// Throws io_error unless every announced frame was added and written.
    void finish() {
        if (written_ != frames_) throw io_error(path_, std::to_string(written_) + " of " + std::to_string(frames_) + " frames were added");
        out_.close();
        if (!out_) throw io_error(path_, "cannot write");
    }

private:
    void write_frame_control() {
        std::vector<std::uint8_t> c;
        detail::put_u32(c, sequence_++);
        detail::put_u32(c, std::uint32_t(width_));
        detail::put_u32(c, std::uint32_t(height_));
        detail::put_u32(c, 0); // x offset
        detail::put_u32(c, 0); // y offset
        c.insert(c.end(), {std::uint8_t(delay_numerator_ >> 8), std::uint8_t(delay_numerator_ & 0xFF), std::uint8_t(delay_denominator_ >> 8),
                           std::uint8_t(delay_denominator_ & 0xFF)});
        c.insert(c.end(), {0, 0}); // dispose: none; blend: source (each frame replaces the last)
        write_chunk("fcTL", c.data(), c.size());
        frame_control_written_ = true;
    }

    void write_chunk(const char (&type)[5], const std::uint8_t* data, std::size_t length) {
        std::vector<std::uint8_t> head;
        detail::put_u32(head, std::uint32_t(length));
        head.insert(head.end(), type, type + 4);
        std::uint32_t crc = detail::png_crc(0, head.data() + 4, 4);
        if (length > 0) crc = detail::png_crc(crc, data, length);
        out_.write(reinterpret_cast<const char*>(head.data()), std::streamsize(head.size()));
        if (length > 0) out_.write(reinterpret_cast<const char*>(data), std::streamsize(length));
        std::vector<std::uint8_t> tail;
        detail::put_u32(tail, crc);
        out_.write(reinterpret_cast<const char*>(tail.data()), 4);
    }

    std::string path_;
    int width_, height_, channels_, frames_;
    std::uint16_t delay_numerator_, delay_denominator_;
    int written_ = 0;
    std::uint32_t sequence_ = 0;
    bool frame_control_written_ = false;
    std::ofstream out_;
};

} // namespace hairshadow
