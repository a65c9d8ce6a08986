#pragma once
// `hairshadow animate`: the methods side by side over frames of moving hair, as an animated PNG (and an
// MP4 where ffmpeg is installed), with a table of each method's error and flicker over time.
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/methods/spec.hpp>

#include <string>

namespace cli {

enum class motion_kind { sway, light, both };

struct animate_options {
    std::string model;
    std::string mesh;                      ///< an OBJ whose faces are the opaque mesh; procedural models get their sphere
    std::string light = "dir:0.6,-1,0.6";  ///< the light at time 0
    std::string methods = hairshadow::example_spec_list(hairshadow::in_animate); ///< the registered families' animation examples
    motion_kind motion = motion_kind::both;
    int frames = 24;
    int fps = 12;
    int resolution = 256;   ///< shadow maps
    int size = 240;         ///< each panel, in pixels
    int supersample = 2;    ///< as figure's: each panel rendered at N x N samples a pixel
    float amplitude = 14.0f; ///< the sway's largest turn of a tip, degrees
    unsigned seed = 1;
    float azimuth = 25.0f, elevation = 10.0f;
    bool full_colour = false; ///< the APNG in full colour rather than one 256-colour palette (a larger file)
    std::string out = "out/animate";
    hairshadow::execution exec;
};

/// Writes animate.png (APNG, in one palette of 256 colours unless full_colour), animate.mp4 when ffmpeg is on the PATH, animate.md and animate.csv into
/// options.out. The animation loops: the sway and the light's orbit each take the whole animation.
int run_animate(const animate_options& options);

} // namespace cli
