#pragma once
/// @file
/// PNG output through stb_image_write (Debian's libstb-dev, `<stb/stb_image_write.h>`), compiled into
/// each including translation unit as static functions so that no link step is needed.

#include <hairshadow/core/error.hpp>

#include <cstdint>
#include <string>
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

/// Writes 8-bit pixels (row-major, top row first, `channels` of 1, 3 or 4) as a PNG.
inline void write_png(const std::string& path, int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
        pixels.size() != std::size_t(width) * std::size_t(height) * std::size_t(channels))
        throw argument_error("write_png: pixel buffer does not match " + std::to_string(width) + "x" + std::to_string(height));
    if (!stbi_write_png(path.c_str(), width, height, channels, pixels.data(), width * channels))
        throw io_error(path, "cannot write PNG");
}

} // namespace hairshadow
