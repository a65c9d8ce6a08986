#pragma once
/// @file
/// PNG and animated PNG (APNG) output through stb_image_write (Debian's libstb-dev, `<stb/stb_image_write.h>`), compiled into
/// each including translation unit as static functions so that no link step is needed.

#include <hairshadow/core/error.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
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

/// How an animated PNG stores its pixels: as given, or as indices into one palette of up to 256
/// colours made from the first frame (median cut, no dithering: a still region stays still), about a
/// third of the size for rendered frames.
enum class png_colours { full, palette };

/// Writes an animated PNG (APNG 1.0: acTL, then an fcTL per frame, the first frame's image data in IDAT
/// so that a viewer without APNG shows it, the others in fdAT), frame by frame as they are made, so a
/// long animation is never held whole. Every frame covers the whole image; the animation loops.
class apng_writer {
public:
    /// Opens `path` for `frame_count` frames of width x height pixels with `channels` (3 or 4), each
    /// shown for delay_numerator / delay_denominator seconds (1/fps: 1, fps), in full colour or in one
    /// palette for every frame (3 channels). Throws argument_error for sizes PNG cannot hold or a zero
    /// denominator, before touching the file; io_error if it cannot write.
    apng_writer(const std::string& path, int width, int height, int channels, int frame_count, std::uint16_t delay_numerator,
                std::uint16_t delay_denominator, png_colours colours = png_colours::full)
        : path_(path), width_(width), height_(height), channels_(channels), frames_(frame_count), delay_numerator_(delay_numerator),
          delay_denominator_(delay_denominator), colours_(colours) {
        if (width <= 0 || height <= 0 || (channels != 3 && channels != 4) || frame_count <= 0 || delay_denominator == 0 ||
            (colours == png_colours::palette && channels != 3))
            throw argument_error("apng_writer: needs a positive size and frame count, 3 or 4 channels (3 with a palette) and a non-zero "
                                 "delay denominator");
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
        std::vector<std::uint8_t> header, image;
        if (colours_ == png_colours::palette) indexed_frame(pixels, header, image);
        else stb_frame(pixels, header, image);
        if (written_ == 0) {
            write_chunk("IHDR", header.data(), header.size());
            if (colours_ == png_colours::palette) write_chunk("PLTE", palette_.data(), palette_.size());
            std::vector<std::uint8_t> control;
            detail::put_u32(control, std::uint32_t(frames_));
            detail::put_u32(control, 0); // loop for ever
            write_chunk("acTL", control.data(), control.size());
        }
        write_frame_control();
        if (written_ == 0) write_chunk("IDAT", image.data(), image.size());
        else {
            std::vector<std::uint8_t> chunk;
            detail::put_u32(chunk, sequence_++);
            chunk.insert(chunk.end(), image.begin(), image.end());
            write_chunk("fdAT", chunk.data(), chunk.size());
        }
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
    /// stb's PNG of the frame: its IHDR's data, and its IDAT chunks' data joined (one zlib stream).
    void stb_frame(const std::vector<std::uint8_t>& pixels, std::vector<std::uint8_t>& header, std::vector<std::uint8_t>& image) const {
        int size = 0;
        unsigned char* png = stbi_write_png_to_mem(pixels.data(), width_ * channels_, width_, height_, channels_, &size);
        if (!png) throw io_error(path_, "cannot encode a frame");
        const std::vector<std::uint8_t> encoded(png, png + size);
#ifdef STBIW_FREE
        STBIW_FREE(png); // the user's allocator, where they gave stb one
#else
        std::free(png);
#endif
        // The signature, then chunks: length, type, data, CRC.
        for (std::size_t at = 8; at + 12 <= encoded.size();) {
            const std::uint32_t length = detail::get_u32(&encoded[at]);
            if (length > encoded.size() - at - 12) throw io_error(path_, "stb wrote a chunk past its PNG's end");
            const std::string_view type(reinterpret_cast<const char*>(&encoded[at + 4]), 4);
            const std::uint8_t* data = &encoded[at + 8];
            if (type == "IHDR") header.assign(data, data + length);
            if (type == "IDAT") image.insert(image.end(), data, data + length);
            at += 12 + length;
        }
    }

    /// The frame in the palette made from the first frame: each pixel the nearest of its colours.
    void indexed_frame(const std::vector<std::uint8_t>& pixels, std::vector<std::uint8_t>& header, std::vector<std::uint8_t>& image) {
        if (written_ == 0) make_palette(pixels);
        const std::size_t row = std::size_t(width_) + 1;
        std::vector<std::uint8_t> rows(row * std::size_t(height_), 0); // each row: filter 0 (none), then indices
        for (std::size_t y = 0; y < std::size_t(height_); ++y)
            for (std::size_t x = 0; x < std::size_t(width_); ++x) {
                const std::uint8_t* p = &pixels[(y * std::size_t(width_) + x) * std::size_t(channels_)];
                rows[y * row + 1 + x] = nearest(std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2]);
            }
        int size = 0;
        unsigned char* zlib = stbi_zlib_compress(rows.data(), int(rows.size()), &size, stbi_write_png_compression_level);
        if (!zlib) throw io_error(path_, "cannot compress a frame");
        image.assign(zlib, zlib + size);
#ifdef STBIW_FREE
        STBIW_FREE(zlib);
#else
        std::free(zlib);
#endif
        detail::put_u32(header, std::uint32_t(width_));
        detail::put_u32(header, std::uint32_t(height_));
        header.insert(header.end(), {8, 3, 0, 0, 0}); // 8-bit indices into PLTE; deflate, adaptive filters, no interlace
    }

    /// Up to 256 colours: every colour of the first frame where it has no more, else median cut (each
    /// box of colours split at its median along its widest channel, the most varied box first).
    void make_palette(const std::vector<std::uint8_t>& pixels) {
        std::vector<std::uint32_t> colours;
        colours.reserve(pixels.size() / std::size_t(channels_));
        for (std::size_t i = 0; i < pixels.size(); i += std::size_t(channels_))
            colours.push_back(std::uint32_t(pixels[i]) << 16 | std::uint32_t(pixels[i + 1]) << 8 | pixels[i + 2]);
        std::vector<std::uint32_t> distinct = colours;
        std::sort(distinct.begin(), distinct.end());
        distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
        std::vector<std::uint32_t> chosen;
        if (distinct.size() <= 256) chosen = distinct;
        else {
            const auto channel = [](std::uint32_t c, int k) { return int(c >> (16 - 8 * k) & 0xFFu); };
            struct box { std::size_t begin, end; int spread, widest; };
            const auto measure = [&](std::size_t b, std::size_t e) {
                box out{b, e, -1, 0};
                for (int k = 0; k < 3; ++k) {
                    int lo = 255, hi = 0;
                    for (std::size_t i = b; i < e; ++i) lo = std::min(lo, channel(colours[i], k)), hi = std::max(hi, channel(colours[i], k));
                    if (hi - lo > out.spread) out.spread = hi - lo, out.widest = k;
                }
                return out;
            };
            std::vector<box> boxes{measure(0, colours.size())};
            while (boxes.size() < 256) {
                auto widest = std::max_element(boxes.begin(), boxes.end(), [](const box& a, const box& b) { return a.spread < b.spread; });
                if (widest->spread <= 0) break;
                const box b = *widest;
                const std::size_t mid = b.begin + (b.end - b.begin) / 2;
                std::nth_element(colours.begin() + std::ptrdiff_t(b.begin), colours.begin() + std::ptrdiff_t(mid), colours.begin() + std::ptrdiff_t(b.end),
                                 [&](std::uint32_t x, std::uint32_t y) { return channel(x, b.widest) < channel(y, b.widest); });
                *widest = measure(b.begin, mid);
                boxes.push_back(measure(mid, b.end));
            }
            for (const box& b : boxes) {
                std::uint64_t sum[3] = {0, 0, 0};
                for (std::size_t i = b.begin; i < b.end; ++i)
                    for (int k = 0; k < 3; ++k) sum[k] += std::uint64_t(channel(colours[i], k));
                const std::uint64_t n = b.end - b.begin;
                chosen.push_back(std::uint32_t((sum[0] + n / 2) / n) << 16 | std::uint32_t((sum[1] + n / 2) / n) << 8 | std::uint32_t((sum[2] + n / 2) / n));
            }
        }
        palette_.clear();
        for (const std::uint32_t c : chosen) palette_.insert(palette_.end(), {std::uint8_t(c >> 16), std::uint8_t(c >> 8), std::uint8_t(c)});
        chosen_ = std::move(chosen);
    }

    /// The palette index nearest `colour` (squared RGB distance, the lowest index on ties), remembered.
    std::uint8_t nearest(std::uint32_t colour) {
        if (const auto hit = nearest_.find(colour); hit != nearest_.end()) return hit->second;
        if (nearest_.size() > (1u << 20)) nearest_.clear(); // a bound on the memory a long animation holds
        int best = 0, best_distance = std::numeric_limits<int>::max();
        for (std::size_t i = 0; i < chosen_.size(); ++i) {
            int d = 0;
            for (int shift : {16, 8, 0}) {
                const int e = int(colour >> shift & 0xFFu) - int(chosen_[i] >> shift & 0xFFu);
                d += e * e;
            }
            if (d < best_distance) best_distance = d, best = int(i);
        }
        return nearest_[colour] = std::uint8_t(best);
    }

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
    png_colours colours_;
    std::vector<std::uint8_t> palette_;       ///< PLTE's data
    std::vector<std::uint32_t> chosen_;       ///< the palette as 0xRRGGBB
    std::unordered_map<std::uint32_t, std::uint8_t> nearest_;
    std::ofstream out_;
};

} // namespace hairshadow
