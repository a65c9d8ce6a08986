#pragma once
// The measurements of `hairshadow compare` (and of the Python module's compare()): each method built
// on the chosen back end and measured against the exact map built on the CPU, at the model's points,
// along each texel's ray and in a rendered image.
#include "command_line.hpp"
#include "compare_table.hpp"

#include <string>
#include <vector>

namespace cli {

/// The rows of a comparison, and the sentence that says how they were measured.
struct comparison {
    std::vector<compare_row> rows;
    std::string preamble;
};

/// Builds the exact map on the CPU and each of `specs` on o's back end, and measures each method's
/// errors against it (compare_row's columns); the model and GL context from `source` where given.
/// With `reference_file`, the reference is that deep OpenEXR image (io/deep_exr.hpp) instead, its
/// own light mapping the points; where that light is not the one fitted here, the curve error (which
/// compares texel by texel) is NaN and the preamble says why.
comparison compare_methods(const map_options& o, const std::vector<hairshadow::method_spec>& specs, const scene_source& source = {},
                           const std::string& reference_file = {});

} // namespace cli
