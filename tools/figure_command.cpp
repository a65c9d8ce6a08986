// The comparison figure, in the manner of Kim & Neumann's Figure 1, Yuksel & Keyser's Figure 3 and
// Sintorn & Assarsson's Figure 5: the same shaded hair with no shadows, with each method and with the
// exact reference, each labelled with its build time; enlarged crops of one region; heat maps of
// |T - T_exact| at the hair; the transmittance along a few light rays (SVG, as Sintorn & Assarsson's
// Fig. 5 and Mertens et al.'s Fig. 5); and the comparison table.
#include "figure.hpp"
#include "command_line.hpp"

#include "compare_table.hpp"
#include "memory_chart.hpp"
#include "panel_grid.hpp"
#include "progress.hpp"
#include "scene_setup.hpp"
#include "text.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/obj_format.hpp>
#include <hairshadow/io/png.hpp>
#include <hairshadow/methods/registry.hpp>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

namespace cli {
namespace {

using namespace hairshadow;
namespace fs = std::filesystem;

/// One column of the figure: a method (or none) with its maps and build time.
struct panel {
    std::string label, spec;
    std::unique_ptr<any_shadow_map> map; ///< null: no shadows
    double build_ms = 0;
    image picture; ///< the panel, averaged down from `detail`
    image detail;  ///< the crop's region, rendered at supersample times the panel's size
};

/// A colour ramp for errors in [0, 1]: black, blue, magenta, orange, yellow.
glm::vec3 heat(float v) {
    static const glm::vec3 stops[] = {{0.02f, 0.02f, 0.05f}, {0.10f, 0.15f, 0.75f}, {0.75f, 0.10f, 0.55f}, {1.0f, 0.45f, 0.05f}, {1.0f, 1.0f, 0.35f}};
    const float x = (v > 0.0f ? std::min(v, 1.0f) : 0.0f) * 4.0f; // NaN counts as 0
    const int i = std::min(3, int(x));
    return stops[i] + (x - float(i)) * (stops[i + 1] - stops[i]);
}

void outline(image& img, int x0, int y0, int w, int h, const glm::vec3& colour) {
    for (int x = x0; x < x0 + w; ++x)
        for (int y : {y0, y0 + h - 1}) img.at(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1)) = colour;
    for (int y = y0; y < y0 + h; ++y)
        for (int x : {x0, x0 + w - 1}) img.at(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1)) = colour;
}

image crop(const image& src, int x0, int y0, int w, int h) {
    image out(w, h, glm::vec3(0.0f));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y) = src.at(std::clamp(x0 + x, 0, src.width - 1), std::clamp(y0 + y, 0, src.height - 1));
    return out;
}

/// Texels whose rays cross many fragments: ranks 1%, 5%, 20% and 50% of the occupied texels by count.
std::vector<std::pair<int, int>> interesting_rays(const fragment_buffer& fragments) {
    std::vector<std::pair<std::size_t, std::size_t>> counts; // (count, texel)
    for (std::size_t t = 0; t < fragments.texel_count(); ++t)
        if (const auto n = fragments.texel(t).size(); n > 0) counts.push_back({n, t});
    std::sort(counts.begin(), counts.end(), [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
    std::vector<std::pair<int, int>> rays;
    if (counts.empty()) return rays;
    const int res = fragments.resolution();
    for (double rank : {0.01, 0.05, 0.2, 0.5}) {
        const auto t = counts[std::min(counts.size() - 1, std::size_t(rank * double(counts.size())))].second;
        rays.push_back({int(t % std::size_t(res)), int(t / std::size_t(res))});
    }
    return rays;
}

/// The transmittance along each ray, the exact reference against each method, as SVG line plots.
std::string ray_plots(const std::vector<panel>& panels, const fragment_buffer& fragments, const std::string& credit) {
    static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"};
    const auto rays = interesting_rays(fragments);
    const int pw = 330, ph = 240, margin = 40, legend = 150;
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << int(rays.size()) * pw + legend << "\" height=\"" << ph + (credit.empty() ? 20 : 40)
        << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (std::size_t r = 0; r < rays.size(); ++r) {
        const auto [x, y] = rays[r];
        const auto frags = fragments.texel(x, y);
        float lo = frags[0].depth, hi = lo;
        for (const auto& f : frags) lo = std::min(lo, f.depth), hi = std::max(hi, f.depth);
        const float pad = 0.08f * std::max(hi - lo, 1e-4f), d0 = lo - pad, d1 = hi + pad;
        const int ox = int(r) * pw + margin, oy = 20, w = pw - margin - 10, h = ph - 60;
        svg << "<text x=\"" << ox << "\" y=\"14\">texel (" << x << ", " << y << "): " << frags.size() << " fragments</text>\n";
        svg << "<rect x=\"" << ox << "\" y=\"" << oy << "\" width=\"" << w << "\" height=\"" << h << "\" fill=\"none\" stroke=\"#444\"/>\n";
        svg << "<text x=\"" << ox - 6 << "\" y=\"" << oy + 4 << "\" text-anchor=\"end\">1</text><text x=\"" << ox - 6 << "\" y=\"" << oy + h
            << "\" text-anchor=\"end\">0</text>\n";
        svg << "<text x=\"" << ox + w / 2 << "\" y=\"" << oy + h + 16 << "\" text-anchor=\"middle\">depth along the light ray</text>\n";
        svg << "<text x=\"" << ox - 28 << "\" y=\"" << oy + h / 2 << "\" transform=\"rotate(-90 " << ox - 28 << " " << oy + h / 2
            << ")\" text-anchor=\"middle\">T</text>\n";
        std::size_t colour = 0;
        for (const auto& p : panels) {
            if (!p.map) continue;
            const bool exact = p.spec == "dsm";
            svg << "<polyline fill=\"none\" stroke=\"" << (exact ? "#000" : colours[colour++ % 8]) << "\" stroke-width=\"" << (exact ? 2.2 : 1.3)
                << "\" points=\"";
            for (int i = 0; i <= 240; ++i) {
                const float depth = d0 + (d1 - d0) * float(i) / 240.0f;
                svg << ox + double(w) * i / 240.0 << "," << oy + double(h) * (1.0 - double(p.map->transmittance(x, y, depth))) << " ";
            }
            svg << "\"/>\n";
        }
    }
    const int lx = int(rays.size()) * pw + 5;
    std::size_t colour = 0;
    int ly = 30;
    for (const auto& p : panels) {
        if (!p.map) continue;
        const bool exact = p.spec == "dsm";
        svg << "<line x1=\"" << lx << "\" y1=\"" << ly << "\" x2=\"" << lx + 24 << "\" y2=\"" << ly << "\" stroke=\"" << (exact ? "#000" : colours[colour++ % 8])
            << "\" stroke-width=\"2\"/><text x=\"" << lx + 30 << "\" y=\"" << ly + 4 << "\">" << p.label << "</text>\n";
        ly += 18;
    }
    if (!credit.empty()) svg << "<text x=\"6\" y=\"" << ph + 32 << "\" fill=\"#555\">" << credit << "</text>\n";
    svg << "</svg>\n";
    return svg.str();
}

/// The figure's scene as the light sees it, and what every step after the maps shares.
struct figure_scene {
    scene sc;
    light_space space;
    fragment_buffer fragments; ///< for the ray plots and the curve error: the maps are built without them
    depth_shadow_map mesh_shadow;
    std::string credit;
};

/// The panels: no shadows, each method, the exact reference; each map built straight from the model
/// (tile by tile; the exact reference through a fragment buffer), twice: the label gives the
/// rebuild, as a renderer rebuilding every frame sees it.
std::vector<panel> build_panels(const figure_options& o, const figure_scene& f) {
    std::vector<panel> panels;
    panels.push_back({pretty("none"), "none", nullptr, 0, {}, {}});
    for (auto part : detail::split(o.methods, ',')) panels.push_back({pretty(std::string(part)), std::string(part), nullptr, 0, {}, {}});
    panels.push_back({pretty("dsm"), "dsm", nullptr, 0, {}, {}});
    for (auto& p : panels) {
        if (p.spec == "none") continue;
        p.map = make_shadow_map(p.spec); // throws spec_error for a bad spec, before any work
    }
    raster_options raster;
    raster.exec = o.exec;
    for (auto& p : panels) {
        if (!p.map) continue;
        step("building " + p.spec, [&] { p.map->build(f.sc.hair, f.space, raster); });
        const auto start = std::chrono::steady_clock::now();
        p.map->build(f.sc.hair, f.space, raster);
        p.build_ms = ms_since(start);
    }
    return panels;
}

/// How the panels are drawn: the camera, its render options and the crop (upper middle, the hair).
struct panel_view {
    camera cam;
    render_options ro;
    int k, cw, cx, cy;
    panel_view(const figure_options& o, const scene& sc)
        : cam(camera::framing(sc.bounds(), o.azimuth, o.elevation, o.size, o.size, 1.15f)), k(o.supersample), cw(o.size / 4),
          cx(o.size * 11 / 20 - cw / 2), cy(o.size * 7 / 20 - cw / 2) {
        ro.exec = o.exec;
        ro.supersample = o.supersample;
    }
};

/// Renders every panel at k x k its size (then averaged down) and its crop; gives the pixels the
/// hair covers (the same in every panel), for the image error.
std::vector<float> render_panels(const figure_options& o, const figure_scene& f, const panel_view& v, std::vector<panel>& panels) {
    const auto supersampled = detail::supersampled(v.cam, v.ro); // every panel at k x k its size, then averaged down
    const camera& detail_cam = supersampled.first;
    const render_options& detail_ro = supersampled.second;
    std::vector<float> detail_coverage(std::size_t(detail_cam.width) * std::size_t(detail_cam.height));
    for (auto& p : panels) {
        const std::vector<lit_light> lights{{f.sc.lights[0], p.map ? query_of(*p.map, o.exec) : transmittance_query{}, f.mesh_shadow}};
        const image full = step("rendering " + p.label, [&] { return render_cpu(f.sc, detail_cam, lights, detail_ro, detail_coverage); });
        p.picture = downsample(full, v.k);
        p.detail = crop(full, v.cx * v.k, v.cy * v.k, v.cw * v.k, v.cw * v.k);
    }
    std::vector<float> coverage(std::size_t(o.size) * std::size_t(o.size), 0.0f);
    for (int y = 0; y < detail_cam.height; ++y)
        for (int x = 0; x < detail_cam.width; ++x)
            coverage[std::size_t(y / v.k) * std::size_t(o.size) + std::size_t(x / v.k)] +=
                detail_coverage[std::size_t(y) * std::size_t(detail_cam.width) + std::size_t(x)] / float(v.k * v.k);
    return coverage;
}

/// figure.png: the panels, labelled with build times, the crop region outlined, and what was drawn.
void write_panels(const figure_options& o, const figure_scene& f, const panel_view& v, const std::vector<panel>& panels) {
    std::vector<image> cells;
    std::vector<std::string> labels;
    char label[128];
    for (const auto& p : panels) {
        image cell = p.picture;
        outline(cell, v.cx, v.cy, v.cw, v.cw, glm::vec3(0.9f, 0.1f, 0.1f));
        cells.push_back(cell);
        std::snprintf(label, sizeof label, p.map ? "%s  %.0f ms" : "%s", p.label.c_str(), p.build_ms);
        labels.push_back(label);
    }
    if (cells.size() % 4 != 0) { // the last cell of the grid: what was drawn
        image info(o.size, o.size, paper);
        int y = 20;
        for (const std::string& line : {"model: " + fs::path(o.model).filename().string(), std::string("light: ") + o.light,
                                        "maps: " + std::to_string(o.resolution) + "x" + std::to_string(o.resolution),
                                        std::to_string(f.sc.hair.strand_count()) + " strands, " + std::to_string(f.sc.hair.segment_count()) + " segments",
                                        std::to_string(f.fragments.size()) + " fragments", std::string("times: a CPU rebuild each")}) {
            draw_text(info, 10, y, line, ink);
            y += 26;
        }
        cells.push_back(info);
        labels.push_back("");
    }
    save(fs::path(o.out) / "figure.png", grid(cells, labels, 4, f.credit));
}

/// crops.png: the crops, enlarged three times, from the supersampled render, so that enlarging shows
/// detail rather than pixels (nearest neighbours only where it has fewer than three times the pixels).
void write_crops(const figure_options& o, const figure_scene& f, const panel_view& v, const std::vector<panel>& panels) {
    std::vector<image> crops;
    std::vector<std::string> crop_labels;
    for (const auto& p : panels) {
        image big(3 * v.cw, 3 * v.cw, paper);
        for (int y = 0; y < big.height; ++y)
            for (int x = 0; x < big.width; ++x)
                big.at(x, y) = p.detail.at(std::min(x * v.k / 3, p.detail.width - 1), std::min(y * v.k / 3, p.detail.height - 1));
        crops.push_back(big);
        crop_labels.push_back(p.label);
    }
    save(fs::path(o.out) / "crops.png", grid(crops, crop_labels, 4, f.credit));
}

/// The colour bar of the heat maps, as a cell of their grid.
image heat_bar(int size) {
    image bar(size, size, paper);
    for (int y = 40; y < size - 40; ++y)
        for (int x = size / 2 - 20; x < size / 2 + 20; ++x) bar.at(x, y) = heat(1.0f - float(y - 40) / float(std::max(1, size - 81)));
    draw_text(bar, size / 2 + 28, 36, "0.5 or more", ink);
    draw_text(bar, size / 2 + 28, size - 50, "0", ink);
    return bar;
}

/// heatmaps.png: |T - T_exact| at the hair points, the mesh in grey; gives the table's rows.
std::vector<compare_row> write_heatmaps(const figure_options& o, const figure_scene& f, const panel_view& v, const std::vector<panel>& panels,
                                        std::span<const float> coverage) {
    const auto& sc = f.sc;
    const auto& exact = *panels.back().map;
    const image& exact_picture = panels.back().picture;
    std::vector<float> reference(sc.hair.point_count()), t(sc.hair.point_count());
    step("the reference at the hair points", [&] { exact.transmittance(sc.hair.points, reference, {}, o.exec); });
    const auto surface = detail::rasterise_mesh(sc.mesh, v.cam, o.exec);
    std::vector<image> heat_cells;
    std::vector<std::string> heat_labels;
    std::vector<compare_row> rows;
    char label[128];
    for (const auto& p : panels) {
        if (!p.map || p.spec == "dsm") continue;
        p.map->transmittance(sc.hair.points, t, {}, o.exec);
        std::vector<glm::vec3> colours(t.size());
        for (std::size_t i = 0; i < t.size(); ++i) colours[i] = heat(std::abs(t[i] - reference[i]) / 0.5f);
        image cell(o.size, o.size, glm::vec3(0.02f));
        for (std::size_t i = 0; i < surface.inv_w.size(); ++i)
            if (surface.inv_w[i] > 0.0f) cell.pixels[i] = glm::vec3(0.12f);
        draw_hair_lines(cell, sc.hair, colours, v.cam, surface.inv_w, v.ro);
        compare_row row{p.spec, p.map->layer_count(), p.map->memory_bytes(), p.build_ms};
        set_errors(row, t, reference);
        row.curve = transmittance_curve_error(*p.map, exact, f.fragments, 64, o.exec);
        const auto seen = image_error(p.picture, exact_picture, coverage);
        row.image_mean = seen.mean;
        row.image_p99 = seen.p99;
        rows.push_back(row);
        std::snprintf(label, sizeof label, "%s  mean %.3f", p.label.c_str(), row.mean);
        heat_cells.push_back(cell);
        heat_labels.push_back(label);
    }
    heat_cells.push_back(heat_bar(o.size));
    heat_labels.push_back("|T - T_exact|");
    save(fs::path(o.out) / "heatmaps.png", grid(heat_cells, heat_labels, 3, f.credit));
    return rows;
}

/// compare.md and compare.csv: the rows, the exact reference's last, after what was measured and how.
void write_figure_table(const figure_options& o, const figure_scene& f, const std::vector<panel>& panels, std::vector<compare_row> rows,
                        const image_difference& unshadowed) {
    rows.push_back({"dsm", 0, panels.back().map->memory_bytes(), panels.back().build_ms});
    std::ostringstream preamble;
    preamble << "Model `" << o.model << "`" << (o.mesh.empty() ? "" : ", mesh `" + o.mesh + "`") << ", light `" << o.light << "`, " << o.resolution
             << "x" << o.resolution << ", " << f.sc.hair.point_count() << " points, " << f.fragments.size() << " fragments, " << o.exec.resolved()
             << " threads. Errors are |T - T_exact| at the hair's points, the curve error the mean over texels of the mean |T - T_exact| "
                "from each texel's first fragment to its last; times are CPU rebuilds straight from the model (rasterise and "
                "build, tile by tile for the methods), the second of two builds.";
    char shadows[256];
    std::snprintf(shadows, sizeof shadows,
                  " The image error is the mean and 99th percentile over the %zu hair pixels of |sRGB difference| from the exact panel "
                  "(%dx%d supersampled); the panel with no hair shadows differs from the exact one by %.4f (mean), %.4f (p99).",
                  unshadowed.pixels, o.supersample, o.supersample, unshadowed.mean, unshadowed.p99);
    preamble << shadows;
    if (!f.credit.empty()) preamble << " " << f.credit << ".";
    const auto [md, csv] = format_table(rows, preamble.str());
    write_table(o.out, md, csv);
    std::fputs(md.c_str(), stdout);
}

} // namespace

int run_figure(const figure_options& o) {
    std::fprintf(stderr, "figure of %s\n", o.model.c_str());
    scene sc = load_scene(o.model, o.mesh, {parse_light_spec(o.light)});
    const auto space = light_space::fit(sc.lights[0].spec, sc.bounds(), o.resolution);
    raster_options raster;
    raster.exec = o.exec;
    auto fragments = step("rasterising the hair from the light", [&] { return rasterize(sc.hair, space, raster); });
    auto mesh_shadow = step("the mesh's depth shadow map", [&] { return depth_shadow_map(sc.mesh, space, default_mesh_bias, o.exec); });
    const figure_scene f{std::move(sc), space, std::move(fragments), std::move(mesh_shadow), credit_for(o.model, o.mesh)};
    auto panels = build_panels(o, f);
    const panel_view v(o, f.sc);
    const auto coverage = render_panels(o, f, v, panels);
    const image_difference unshadowed = image_error(panels.front().picture, panels.back().picture, coverage);
    fs::create_directories(o.out);
    write_panels(o, f, v, panels);
    write_crops(o, f, v, panels);
    auto rows = write_heatmaps(o, f, v, panels, coverage);
    write_file(fs::path(o.out) / "rays.svg", ray_plots(panels, f.fragments, f.credit));
    std::fprintf(stderr, "wrote %s\n", (fs::path(o.out) / "rays.svg").string().c_str());
    write_file(fs::path(o.out) / "memory.svg", memory_chart_svg(rows, o.resolution, "Image error against memory, " + std::to_string(o.resolution) + "x" +
                                                                                       std::to_string(o.resolution) + (f.credit.empty() ? "" : ": " + f.credit)));
    std::fprintf(stderr, "wrote %s\n", (fs::path(o.out) / "memory.svg").string().c_str());
    write_figure_table(o, f, panels, std::move(rows), unshadowed);
    return 0;
}

int run_transparency_figure(const figure_options& o, float hair_opacity) {
    std::fprintf(stderr, "transparency figure of %s\n", o.model.c_str());
    const std::string credit = credit_for(o.model, o.mesh);
    const scene sc = load_scene(o.model, o.mesh, {parse_light_spec(o.light)});
    const auto space = light_space::fit(sc.lights[0].spec, sc.bounds(), o.resolution);
    occupancy_maps<128, 4> shadows;
    step("occupancy maps 128/4 for the shadows", [&] {
        raster_options ro;
        ro.exec = o.exec;
        shadows.build(sc.hair, space, ro);
    });
    const std::vector<lit_light> lights{{sc.lights[0], query_of(shadows, o.exec), depth_shadow_map(sc.mesh, space, default_mesh_bias, o.exec)}};
    const auto cam = camera::framing(sc.bounds(), o.azimuth, o.elevation, o.size, o.size, 1.15f);
    render_options ro;
    ro.exec = o.exec;
    struct mode_panel {
        transparency mode;
        std::string label;
        image picture;
        double ms = 0;
    };
    std::vector<mode_panel> panels{{transparency::exact, "exact (sorted)", {}, 0},
                                   {transparency::occupancy, "occupancy order", {}, 0},
                                   {transparency::weighted, "weighted average", {}, 0},
                                   {transparency::none, "no transparency", {}, 0}};
    for (auto& p : panels) {
        const auto start = std::chrono::steady_clock::now();
        p.picture = step("rendering, " + p.label, [&] { return render_transparent(sc, cam, lights, p.mode, hair_opacity, ro); });
        p.ms = ms_since(start);
    }
    std::vector<image> cells;
    std::vector<std::string> labels;
    std::ostringstream md;
    md << "Model `" << o.model << "`, " << o.size << "x" << o.size << ", hair opacity " << hair_opacity << ", shadows by occupancy maps 128/4 at "
       << o.resolution << "x" << o.resolution << ", " << o.exec.resolved() << " threads; times are whole CPU renders."
       << (credit.empty() ? "" : " " + credit + ".") << "\n\n"
       << "| blending | render (ms) | mean abs. difference from exact (sRGB) |\n|---|---|---|\n";
    char label[160];
    for (const auto& p : panels) {
        const double error = mean_absolute_difference(p.picture, panels[0].picture);
        std::snprintf(label, sizeof label, "%s  %.0f ms  error %.4f", p.label.c_str(), p.ms, error);
        cells.push_back(p.picture);
        labels.push_back(label);
        std::snprintf(label, sizeof label, "| %s | %.0f | %.4f |\n", p.label.c_str(), p.ms, error);
        md << label;
    }
    fs::create_directories(o.out);
    save(fs::path(o.out) / "transparency.png", grid(cells, labels, 2, credit));
    write_file(fs::path(o.out) / "transparency.md", md.str());
    std::fputs(md.str().c_str(), stdout);
    return 0;
}

namespace {
struct figure_args {
    figure_options options;
    float transparency_opacity = 0.0f; ///< > 0: the transparency figure instead
};

int run_figure_command(const map_options& o, figure_args& a) {
    auto& fig = a.options;
    try { // everything a usage error can be, before any work
        hairshadow::check_resolution(fig.resolution);
        if (fig.size * fig.supersample > 8192) throw hairshadow::argument_error("--size times --supersample must be at most 8192 pixels");
    } catch (const hairshadow::argument_error& e) {
        throw usage_error(e.what());
    }
    check_model_spec(fig.model);
    check_method_list(fig.methods);
    parse_light(fig.light);
    fig.exec = o.exec();
    return a.transparency_opacity > 0.0f ? run_transparency_figure(fig, a.transparency_opacity) : run_figure(fig);
}
} // namespace

command add_figure_command(CLI::App& app, map_options& o) {
    auto a = std::make_shared<figure_args>();
    auto& fig = a->options;
    auto* cmd = app.add_subcommand("figure", "the comparison figure: shaded hair with each method, crops, error heat maps, ray plots, table");
    cmd->add_option("--model", fig.model, "a model file or " + std::string(hairshadow::procedural_grammar) + " (procedural models stand on their sphere)");
    cmd->add_option("--mesh", fig.mesh, "an OBJ whose faces are the opaque mesh (e.g. the Sintel head)");
    cmd->add_option("--light", fig.light, "light spec: " + std::string(hairshadow::light_grammar));
    cmd->add_option("--methods", fig.methods, "comma-separated method specs between 'no shadows' and the exact reference")->capture_default_str();
    cmd->add_option("--res", fig.resolution, "shadow map resolution")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    cmd->add_option("--size", fig.size, "panel size in pixels")->check(CLI::Range(16, 4096));
    cmd->add_option("--supersample", fig.supersample, "render each panel at N x N samples a pixel (1 to 8; --size times N at most 8192)")
        ->check(CLI::Range(1, 8));
    cmd->add_option("--azimuth", fig.azimuth, "camera azimuth in degrees about +y")->check(finite_number);
    cmd->add_option("--elevation", fig.elevation, "camera elevation in degrees")->check(finite_number & CLI::Range(-89.0f, 89.0f));
    cmd->add_option("--out", fig.out, "output folder");
    cmd->add_option("--transparency", a->transparency_opacity,
                    "instead: the transparency figure (exact, occupancy-ordered, weighted, opaque) with this hair opacity")
        ->check(finite_number & CLI::Range(0.001f, 1.0f));
    return {cmd, [&o, a] { return run_figure_command(o, *a); }};
}

} // namespace cli
