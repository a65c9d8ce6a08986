#pragma once
// `hairshadow figure`: the comparison figure of the papers' Figures 1, 3 and 5 (see figure_command.cpp).
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/methods/spec.hpp>

#include <string>

namespace cli {

struct figure_options {
    std::string model = "procedural:curly";
    std::string mesh; ///< an OBJ whose faces are the opaque mesh; procedural models get their sphere
    std::string light = "dir:0.6,-1,0.6"; ///< from above and behind the left: the camera sees the self-shadowed side
    std::string methods = hairshadow::example_spec_list(hairshadow::in_figure); ///< the registered families' figure examples
    int resolution = 512;    ///< shadow maps
    int size = 400;          ///< each panel, in pixels
    int supersample = 3;     ///< render each panel at this many times its size on each side (1 to 8), then average
    float azimuth = 25.0f, elevation = 10.0f;
    std::string out = "out/figure";
    hairshadow::execution exec;
};

/// Writes figure.png, crops.png, heatmaps.png, rays.svg, memory.svg, compare.md and compare.csv into options.out.
int run_figure(const figure_options& options);

/// Writes transparency.png and transparency.md into options.out: the hair blended exactly (sorted),
/// by occupancy order, by weighted averages and opaque, in the manner of Sintorn & Assarsson's Fig. 2,
/// with times and the error against exact blending; occupancy maps 128/4 shadow every panel.
int run_transparency_figure(const figure_options& options, float hair_opacity);

} // namespace cli
