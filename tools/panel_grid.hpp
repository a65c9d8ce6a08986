#pragma once
// What `figure` and `animate` share: panel labels for method specs, the labelled grid of panels, the
// Sintel credit, and PNG output with a note on stderr.
#include "text.hpp"

#include <hairshadow/io/png.hpp>
#include <hairshadow/shading/image.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace cli {

inline const glm::vec3 ink{0.05f, 0.05f, 0.05f}, paper{1.0f, 1.0f, 1.0f};

/// A method spec as a panel label: "dom:3" is "DOM 3", "occ:128:4" is "OCC 128/4".
inline std::string pretty(const std::string& spec) {
    if (spec == "none") return "no hair shadows";
    if (spec == "dsm") return "exact (deep shadow map)";
    std::string out = spec;
    for (auto& c : out) c = c == ':' ? ' ' : char(std::toupper(static_cast<unsigned char>(c)));
    const auto slash = out.find(' ', out.find(' ') + 1);
    if (out.starts_with("OCC") && slash != std::string::npos) out[slash] = '/';
    return out;
}

/// Copies `src` into `dst` at (x0, y0), each pixel `scale` x `scale` times, clipped to `dst`.
inline void blit(hairshadow::image& dst, const hairshadow::image& src, int x0, int y0, int scale = 1) {
    for (int y = 0; y < src.height * scale; ++y)
        for (int x = 0; x < src.width * scale; ++x)
            if (x0 + x < dst.width && y0 + y < dst.height) dst.at(x0 + x, y0 + y) = src.at(x / scale, y / scale);
}

inline void save(const std::filesystem::path& path, const hairshadow::image& img) {
    hairshadow::write_png(path.string(), img.width, img.height, 3, img.to_srgb8());
    std::fprintf(stderr, "wrote %s (%dx%d)\n", path.string().c_str(), img.width, img.height);
}

/// The credit every image of a model must carry: the Sintel model's (its README in ../shared asks
/// for the Blender Foundation and BenDansie wherever an image of it is shown); none for others.
inline std::string credit_for(const std::string& model, const std::string& mesh) {
    namespace fs = std::filesystem;
    std::string names = fs::path(model).filename().string() + " " + fs::path(mesh).filename().string();
    for (auto& c : names) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (names.find("sintel") == std::string::npos) return "";
    return "Sintel hair and head: Blender Foundation (Sintel, CC-BY 3.0), Sintel Lite by BenDansie";
}

/// A labelled grid of equally sized images, each label above its image and inside its column (see
/// grid_layout), and an optional credit line below.
inline hairshadow::image grid(const std::vector<hairshadow::image>& cells, const std::vector<std::string>& labels, int columns,
                              const std::string& credit = "") {
    const int w = cells.front().width, h = cells.front().height;
    const auto layout = grid_layout(labels, w, h, columns);
    const label_layout credit_lines = layout_label(credit, columns * w);
    const int credit_height = credit.empty() ? 0 : credit_lines.height + 2 * label_margin;
    hairshadow::image out(columns * w, layout.height + credit_height, paper);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto& box = layout.labels[i];
        draw_label(out, box.x, box.y, box.text, ink);
        blit(out, cells[i], box.cell_x, box.cell_y);
    }
    if (!credit.empty()) draw_label(out, label_margin, layout.height + label_margin, credit_lines, glm::vec3(0.3f));
    return out;
}

} // namespace cli
