// Figure labels laid out by their measured width (tools/text.hpp): every line inside its panel,
// nothing lost, rows as tall as their tallest label, for long labels and small panels.
#include "../tools/text.hpp"

#include <catch2/catch.hpp>

#include <sstream>

namespace {
/// The words of `text`, without the spaces between them.
std::string words(const std::string& text) {
    std::istringstream in(text);
    std::string word, out;
    while (in >> word) out += word;
    return out;
}
} // namespace

TEST_CASE("labels break into lines that stay inside their panels", "[figure][labels]") {
    const std::vector<std::string> labels = {
        "exact (sorted)  1234 ms  error 0.0000", "occupancy order  98 ms  error 0.0123", "OSM 512 GAMMA 8BIT  1234 ms",
        "adsm:0.4:0.0021:0.35:50 with a very long name that goes on and on", "DOCC 256/8", "", "averyveryverylongwordwithoutanyspaces"};
    for (const int panel : {64, 100, 200, 400}) {
        for (const int columns : {1, 2, 3}) {
            CAPTURE(panel, columns);
            const auto plan = cli::grid_layout(labels, panel, panel, columns);
            REQUIRE(plan.labels.size() == labels.size());
            for (std::size_t i = 0; i < labels.size(); ++i) {
                const auto& g = plan.labels[i];
                CAPTURE(labels[i], g.x, g.y, g.text.width, g.text.height);
                const int column = int(i) % columns;
                // The label's box lies inside its own column and above its own image.
                CHECK(g.cell_x == column * panel);
                CHECK(g.x >= g.cell_x);
                CHECK(g.x + g.text.width <= g.cell_x + panel);
                CHECK(g.y + g.text.height <= g.cell_y);
                // Every line is measured within the panel's room, and no word is lost.
                std::string joined;
                for (const auto& line : g.text.lines) {
                    CHECK(cli::text_width(line) <= panel - 2 * cli::label_margin);
                    joined += line;
                }
                CHECK(words(joined) == words(labels[i]));
            }
            // Rows do not overlap: each row starts below the previous row's images.
            for (std::size_t i = std::size_t(columns); i < labels.size(); ++i)
                CHECK(plan.labels[i].y >= plan.labels[i - std::size_t(columns)].cell_y + panel);
            CHECK(plan.height == plan.labels.back().cell_y + panel);
        }
    }
    // A label that fits stays on one line.
    CHECK(cli::layout_label("DOM 3  7 ms", 400).lines.size() == 1);
    CHECK(cli::layout_label("exact (sorted)  1234 ms  error 0.0000", 400).lines.size() == 2);
}
