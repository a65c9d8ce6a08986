#pragma once
// Labels on figures: stb_easy_font's quads filled into an image, scaled by an integer factor.
#include <hairshadow/shading/image.hpp>

#include <stb/stb_easy_font.h>

#include <string>
#include <vector>

namespace cli {

/// `text` with every byte stb_easy_font has no glyph for (outside ' '..'~') shown as '?'.
inline std::string printable(std::string text) {
    for (auto& c : text)
        if (c != '\n' && (c < ' ' || c > '~')) c = '?';
    return text;
}

/// Draws `text` with its top-left corner at (x, y), `scale` pixels per font unit, in `colour`.
inline void draw_text(hairshadow::image& img, int x, int y, const std::string& text, const glm::vec3& colour, int scale = 2) {
    struct vertex {
        float x, y, z;
        unsigned char colour[4];
    };
    std::vector<vertex> quads(text.size() * 70 + 4); // stb_easy_font's bound: at most ~270 bytes a character
    std::string copy = printable(text);
    const int count = stb_easy_font_print(0, 0, copy.data(), nullptr, quads.data(), int(quads.size() * sizeof(vertex)));
    for (int q = 0; q < count; ++q) {
        const vertex* v = &quads[std::size_t(4 * q)];
        const int x0 = x + int(v[0].x) * scale, y0 = y + int(v[0].y) * scale, x1 = x + int(v[2].x) * scale, y1 = y + int(v[2].y) * scale;
        for (int py = std::max(0, y0); py < std::min(img.height, y1); ++py)
            for (int px = std::max(0, x0); px < std::min(img.width, x1); ++px) img.at(px, py) = colour;
    }
}

/// Width in pixels of `text` at `scale`.
inline int text_width(const std::string& text, int scale = 2) {
    std::string copy = printable(text);
    return stb_easy_font_width(copy.data()) * scale;
}

} // namespace cli
