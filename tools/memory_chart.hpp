#pragma once
// Which method for a memory budget: from compare's rows, a chart of image error against bytes per
// texel (one line per method family, SVG: `compare --chart`, the figure's memory.svg) and a table
// of each family's best configuration within budgets of 4 to 64 bytes a texel.
#include "compare_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace cli {

/// A row's family: its spec's name, with `8-bit` where it accumulates in 8 bits ("dom:3:8bit" is
/// "dom 8-bit").
inline std::string family_of(const std::string& spec) {
    const auto colon = spec.find(':');
    std::string family = spec.substr(0, colon);
    if (spec.size() >= 5 && spec.compare(spec.size() - 5, 5, ":8bit") == 0) family += " 8-bit";
    return family;
}

/// `text` safe inside SVG's text and titles.
inline std::string xml_escaped(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else out += c;
    }
    return out;
}

/// Bytes a texel of the maps holds, at `resolution` squared texels.
inline double bytes_per_texel(const compare_row& r, int resolution) { return double(r.bytes) / (double(resolution) * double(resolution)); }

/// The rows grouped by family (in first appearance), each sorted by size.
inline std::vector<std::pair<std::string, std::vector<const compare_row*>>> families_of(const std::vector<compare_row>& rows) {
    std::vector<std::pair<std::string, std::vector<const compare_row*>>> families;
    for (const auto& r : rows) {
        const auto name = family_of(r.method);
        auto it = std::find_if(families.begin(), families.end(), [&](const auto& f) { return f.first == name; });
        if (it == families.end()) it = families.insert(families.end(), {name, {}});
        it->second.push_back(&r);
    }
    for (auto& [name, members] : families)
        std::stable_sort(members.begin(), members.end(), [](const compare_row* a, const compare_row* b) { return a->bytes < b->bytes; });
    return families;
}

/// The chart: image error (mean, over hair pixels, base-10 axis) against bytes per texel (base-2
/// axis), a line and dots per family, each dot's spec in its tooltip.
inline std::string memory_chart_svg(const std::vector<compare_row>& rows, int resolution, const std::string& title) {
    // Ten colours, then the same dashed: every family its own line.
    static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
    static const char* dashes[] = {"", " stroke-dasharray=\"6 3\"", " stroke-dasharray=\"2 2\""};
    const int w = 720, h = 440, left = 70, right = 170, top = 40, bottom = 50;
    const int pw = w - left - right, ph = h - top - bottom;
    double lo = 2.0, hi = 128.0, emin = 1.0, emax = 0.0;
    for (const auto& r : rows) {
        const double b = bytes_per_texel(r, resolution);
        if (b > 0) lo = std::min(lo, b), hi = std::max(hi, b);
        if (r.image_mean > 0) emin = std::min(emin, r.image_mean), emax = std::max(emax, r.image_mean);
    }
    lo = std::exp2(std::floor(std::log2(lo))), hi = std::exp2(std::ceil(std::log2(hi)));
    // Errors span decades (0.003 to 0.2 on the test models): a base-10 axis from a 1-2-5 step below
    // the least to one above the largest.
    const auto step_below = [](double v) {
        const double decade = std::pow(10.0, std::floor(std::log10(v)));
        return v >= 5 * decade ? 5 * decade : v >= 2 * decade ? 2 * decade : decade;
    };
    const auto step_above = [](double v) {
        const double decade = std::pow(10.0, std::floor(std::log10(v)));
        for (const double m : {1.0, 2.0, 5.0})
            if (m * decade >= v * 0.9999) return m * decade;
        return 10.0 * decade;
    };
    if (!(emax > 0)) emin = 0.001, emax = 1.0;
    const double elo = step_below(emin), ehi = std::max(step_above(emax), elo * 2.0);
    const auto x_of = [&](double bytes) { return left + pw * (std::log2(std::max(bytes, lo)) - std::log2(lo)) / (std::log2(hi) - std::log2(lo)); };
    const auto y_of = [&](double error) { return top + ph * (std::log10(ehi) - std::log10(std::max(error, elo))) / (std::log10(ehi) - std::log10(elo)); };
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n"
        << "<text x=\"" << left << "\" y=\"20\" font-size=\"13\">" << xml_escaped(title) << "</text>\n"
        << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (double b = lo; b <= hi * 1.001; b *= 2) {
        const double x = x_of(b);
        svg << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << top + ph << "\" stroke=\"#ddd\"/>"
            << "<text x=\"" << x << "\" y=\"" << top + ph + 16 << "\" text-anchor=\"middle\">" << b << "</text>\n";
    }
    for (double decade = std::pow(10.0, std::floor(std::log10(elo))); decade < ehi; decade *= 10)
        for (const double m : {1.0, 2.0, 5.0}) {
            const double e = m * decade;
            if (e < elo * 0.999 || e > ehi * 1.001) continue;
            const double y = y_of(e);
            char label[32];
            std::snprintf(label, sizeof label, "%g", e);
            svg << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + pw << "\" y2=\"" << y << "\" stroke=\"#eee\"/>"
                << "<text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">" << label << "</text>\n";
        }
    svg << "<text x=\"" << left + pw / 2 << "\" y=\"" << h - 12 << "\" text-anchor=\"middle\">bytes per texel (the maps' memory over the texels)</text>\n"
        << "<text x=\"16\" y=\"" << top + ph / 2 << "\" transform=\"rotate(-90 16 " << top + ph / 2
        << ")\" text-anchor=\"middle\">image error (mean |sRGB difference|)</text>\n";
    int colour = 0, legend_y = top + 8;
    for (const auto& [name, members] : families_of(rows)) {
        const char* c = colours[colour % 10];
        const char* dash = dashes[(colour / 10) % 3];
        ++colour;
        svg << "<polyline fill=\"none\" stroke=\"" << c << "\"" << dash << " stroke-width=\"1.6\" points=\"";
        for (const auto* r : members) svg << x_of(bytes_per_texel(*r, resolution)) << "," << y_of(r->image_mean) << " ";
        svg << "\"/>\n";
        for (const auto* r : members)
            svg << "<circle cx=\"" << x_of(bytes_per_texel(*r, resolution)) << "\" cy=\"" << y_of(r->image_mean) << "\" r=\"3\" fill=\"" << c
                << "\"><title>" << xml_escaped(r->method) << "</title></circle>\n";
        svg << "<line x1=\"" << left + pw + 12 << "\" y1=\"" << legend_y << "\" x2=\"" << left + pw + 32 << "\" y2=\"" << legend_y << "\" stroke=\"" << c
            << "\"" << dash << " stroke-width=\"2\"/><text x=\"" << left + pw + 38 << "\" y=\"" << legend_y + 4 << "\">" << xml_escaped(name) << "</text>\n";
        legend_y += 16;
    }
    svg << "</svg>\n";
    return svg.str();
}

/// The budgets of the equal-memory table, in bytes a texel.
inline constexpr int memory_budgets[] = {4, 8, 16, 32, 64};

/// For each budget, each family's configuration of least image error within it ("-" where none
/// fits), and the best of all, as Markdown.
inline std::string budget_table(const std::vector<compare_row>& rows, int resolution) {
    std::ostringstream md;
    md << "\n| family |";
    for (const int b : memory_budgets) md << " " << b << " B/texel |";
    md << "\n|---|";
    for (std::size_t i = 0; i < std::size(memory_budgets); ++i) md << "---|";
    md << "\n";
    const auto best_within = [&](const std::vector<const compare_row*>& members, int budget) {
        // Whole-map state (DOM's extent, OSM's planes, GL's extra row of the range map) does not break
        // a budget: a row and 64 bytes of it are allowed.
        const double allowed = double(budget) * double(resolution) * double(resolution) + 16.0 * double(resolution) + 64.0;
        const compare_row* best = nullptr;
        for (const auto* r : members)
            if (double(r->bytes) <= allowed && (!best || r->image_mean < best->image_mean)) best = r;
        return best;
    };
    std::vector<const compare_row*> all;
    for (const auto& r : rows) all.push_back(&r);
    char cell[160];
    for (const auto& [name, members] : families_of(rows)) {
        md << "| " << name << " |";
        for (const int b : memory_budgets) {
            if (const auto* r = best_within(members, b)) std::snprintf(cell, sizeof cell, " `%s` %.4f |", r->method.c_str(), r->image_mean);
            else std::snprintf(cell, sizeof cell, " - |");
            md << cell;
        }
        md << "\n";
    }
    md << "| **best** |";
    for (const int b : memory_budgets) {
        if (const auto* r = best_within(all, b)) std::snprintf(cell, sizeof cell, " **`%s`** %.4f |", r->method.c_str(), r->image_mean);
        else std::snprintf(cell, sizeof cell, " - |");
        md << cell;
    }
    md << "\n";
    return md.str();
}

} // namespace cli
