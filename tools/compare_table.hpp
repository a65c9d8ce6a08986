#pragma once
// The comparison table shared by `compare` and `figure`: one row per method with its layers, memory,
// build time, the mean, 95th-percentile and maximum |T - T_exact| at the model's points, and the
// transmittance-curve error (reference/transmittance_curve_error.hpp) and the image error
// (shading/image_error.hpp), each measured by the library (reference/, shading/).
#include <hairshadow/core/error.hpp>
#include <hairshadow/reference/point_error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

namespace cli {

struct compare_row {
    std::string method;
    int layers = 0;
    std::size_t bytes = 0;
    double build_ms = 0, mean = 0, p95 = 0, max = 0;
    double curve = 0; ///< mean over texels of the mean |T - T_exact| across the texel's fragments
    double image_mean = 0, image_p99 = 0; ///< |sRGB difference| from the exact map's render, over hair pixels
};

/// Fills the error columns of `row` from a method's and the reference's transmittance.
inline void set_errors(compare_row& row, std::span<const float> t, std::span<const float> reference) {
    const auto e = hairshadow::point_error_of(t, reference);
    row.mean = e.mean, row.p95 = e.p95, row.max = e.max;
}

/// The table as Markdown (after `preamble`) and as CSV.
inline std::pair<std::string, std::string> format_table(const std::vector<compare_row>& rows, const std::string& preamble) {
    std::ostringstream md, csv;
    md << preamble
       << "\n\n| method | layers | memory (MiB) | build (ms) | mean error | 95th percentile | max error | curve error | image error | image p99 |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    csv << "method,layers,memory_bytes,build_ms,mean_error,p95_error,max_error,curve_error,image_error,image_p99\n";
    char line[512];
    for (const auto& r : rows) {
        std::snprintf(line, sizeof line, "| %s | %d | %.2f | %.1f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f |\n", r.method.c_str(), r.layers,
                      double(r.bytes) / 1048576.0, r.build_ms, r.mean, r.p95, r.max, r.curve, r.image_mean, r.image_p99);
        md << line;
        std::snprintf(line, sizeof line, "%s,%d,%zu,%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", r.method.c_str(), r.layers, r.bytes, r.build_ms, r.mean,
                      r.p95, r.max, r.curve, r.image_mean, r.image_p99);
        csv << line;
    }
    return {md.str(), csv.str()};
}

/// Writes `text` to `path`; throws io_error when it cannot.
inline void write_file(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out.good()) throw hairshadow::io_error(path.string(), "cannot write");
}

/// Writes compare.md and compare.csv into `dir`, creating it.
inline void write_table(const std::filesystem::path& dir, const std::string& md, const std::string& csv) {
    std::filesystem::create_directories(dir);
    write_file(dir / "compare.md", md);
    write_file(dir / "compare.csv", csv);
}

} // namespace cli
