#pragma once
// Labels on figures: stb_easy_font's quads filled into an image, scaled by an integer factor.
#include <hairshadow/shading/image.hpp>

#include <stb/stb_easy_font.h>

#include <algorithm>
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

/// Pixels between a label and its panel's edges, and font units from one line to the next.
inline constexpr int label_margin = 6;
inline constexpr int line_units = 12;

/// A label broken into lines that fit a panel: at spaces where it can, inside a word only where the
/// word alone is wider than the panel.
struct label_layout {
    std::vector<std::string> lines;
    int width = 0;  ///< of the widest line, in pixels
    int height = 0; ///< of all lines, in pixels
};

/// `text` laid out for a panel `panel_width` pixels wide: no line wider than panel_width - 2 margins.
inline label_layout layout_label(const std::string& text, int panel_width, int scale = 2) {
    const int room = std::max(1, panel_width - 2 * label_margin);
    label_layout out;
    std::string line;
    const auto flush = [&] {
        if (line.empty()) return;
        out.width = std::max(out.width, text_width(line, scale));
        out.lines.push_back(line);
        line.clear();
    };
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t end = std::min(text.find(' ', start), text.size());
        const std::string word = text.substr(start, end - start);
        start = end + 1;
        if (line.empty() && word.empty()) continue; // no line starts with a space
        if (const std::string joined = line.empty() ? word : line + " " + word; text_width(joined, scale) <= room) {
            line = joined;
            continue;
        }
        flush();
        for (const char c : word) { // the word on lines of its own, cut where it must be
            if (!line.empty() && text_width(line + c, scale) > room) flush();
            line += c;
        }
    }
    flush();
    out.height = int(out.lines.size()) * line_units * scale;
    return out;
}

/// Draws a laid-out label's lines from (x, y) down.
inline void draw_label(hairshadow::image& img, int x, int y, const label_layout& label, const glm::vec3& colour, int scale = 2) {
    for (std::size_t i = 0; i < label.lines.size(); ++i) draw_text(img, x, y + int(i) * line_units * scale, label.lines[i], colour, scale);
}

/// Where each label and image of a labelled grid go: every label inside its column, above its image,
/// each row's label band as tall as the row's tallest label.
struct grid_label {
    label_layout text;
    int x = 0, y = 0;           ///< the label's top-left corner
    int cell_x = 0, cell_y = 0; ///< the image's
};
struct grid_plan {
    std::vector<grid_label> labels;
    int height = 0; ///< of the whole grid
};

inline grid_plan grid_layout(const std::vector<std::string>& labels, int cell_width, int cell_height, int columns, int scale = 2) {
    grid_plan plan;
    const int count = int(labels.size());
    for (int row_start = 0; row_start < count; row_start += columns) {
        const int row_end = std::min(count, row_start + columns);
        int band = line_units * scale;
        for (int i = row_start; i < row_end; ++i) {
            grid_label g;
            g.text = layout_label(labels[std::size_t(i)], cell_width, scale);
            band = std::max(band, g.text.height);
            plan.labels.push_back(std::move(g));
        }
        band += 2 * label_margin;
        for (int i = row_start; i < row_end; ++i) {
            auto& g = plan.labels[std::size_t(i)];
            g.cell_x = (i - row_start) * cell_width;
            g.x = g.cell_x + label_margin;
            g.y = plan.height + label_margin;
            g.cell_y = plan.height + band;
        }
        plan.height += band + cell_height;
    }
    return plan;
}

} // namespace cli
