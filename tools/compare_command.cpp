// `hairshadow compare`: methods against the exact reference at the model's points, along each
// texel's ray and in a rendered image, as a Markdown table (and CSV).
#include "command_line.hpp"
#include "compare_rows.hpp"
#include "memory_chart.hpp"

#include <cstdio>

namespace cli {

using namespace hairshadow;

namespace {
int run_compare(const map_options& o, const std::string& methods, const std::string& out_dir, const std::string& chart, const std::string& reference) {
    std::vector<method_spec> specs;
    for (auto part : detail::split(methods, ',')) specs.push_back(parse_method_for(std::string(part), o));
    const auto [rows, preamble] = compare_methods(o, specs, {}, reference);
    const auto [md, csv] = format_table(rows, preamble);
    std::fputs(md.c_str(), stdout);
    if (!out_dir.empty()) write_table(out_dir, md, csv);
    if (!chart.empty()) {
        // Which method for a memory budget: the chart, and each family's best within each budget.
        write_file(chart, memory_chart_svg(rows, o.resolution, "Image error against memory: " + o.model.substr(o.model.find_last_of('/') + 1) + ", " + std::to_string(o.resolution) + "x" +
                                                                   std::to_string(o.resolution)));
        std::fputs(("\nEach family's configuration of least image error within a budget of bytes a texel:\n" + budget_table(rows, o.resolution)).c_str(),
                   stdout);
    }
    return 0;
}

struct compare_args {
    std::string methods = example_spec_list(in_compare); // the registered families' comparison examples
    std::string out_dir;
    std::string chart;
    std::string reference;
};
} // namespace

command add_compare_command(CLI::App& app, map_options& o) {
    auto a = std::make_shared<compare_args>();
    auto* cmd = app.add_subcommand("compare", "compare methods with the exact reference at the model's points");
    add_model(cmd, o);
    add_map_options(cmd, o, false);
    add_query_options(cmd, o);
    add_backend_options(cmd, o);
    cmd->add_option("--methods", a->methods, "comma-separated method specs")->capture_default_str();
    cmd->add_option("--out", a->out_dir, "also write compare.md and compare.csv into this folder");
    cmd->add_option("--chart", a->chart, "also write a chart of image error against bytes per texel (SVG), and print each family's best within budgets of 4-64 bytes a texel");
    cmd->add_option("--reference", a->reference,
                    "measure against this deep OpenEXR image (hairshadow export) instead of the exact map built here; the file's own light "
                    "maps the model's points, even where it differs from --light and --res (the curve error, texel by texel, is then not measured)");
    return {cmd, [&o, a] { return run_compare(o, a->methods, a->out_dir, a->chart, a->reference); }};
}

} // namespace cli
