// `hairshadow info`: a model's strand, point and segment counts and its bounds.
#include "command_line.hpp"

#include <hairshadow/io/load.hpp>

#include <cstdio>

namespace cli {

using namespace hairshadow;

namespace {
int run_info(const map_options& o) {
    if (!is_procedural_spec(o.model) && model_format_extension(o.model) == ".obj") {
        const auto contents = read_obj(o.model);
        std::printf("mesh:     %zu vertices, %zu triangles\n", contents.mesh.vertices.size(), contents.mesh.triangles.size());
        if (contents.hair.strand_count() == 0) return 0;
    }
    const auto model = load(o.model);
    const auto b = model.bounds();
    std::printf("model:    %s\n", o.model.c_str());
    if (!is_procedural_spec(o.model) && model_format_extension(o.model) == ".tfx") {
        const auto tfx = parse_tfx_file(detail::read_file_bytes(o.model), o.model);
        std::printf("format:   TressFX %d (version %g)", tfx.major_version, double(tfx.version));
        if (tfx.major_version == 3)
            std::printf(", guide strands only: %u follow hairs per guide (not grown)%s", tfx.follow_hairs_per_guide,
                        tfx.both_ends_immovable ? ", both ends immovable" : "");
        std::printf("\n");
    }
    std::printf("strands:  %zu\npoints:   %zu\nsegments: %zu\n", model.strand_count(), model.point_count(), model.segment_count());
    std::printf("bounds:   x [%.6g, %.6g]  y [%.6g, %.6g]  z [%.6g, %.6g]\n", b.min.x, b.max.x, b.min.y, b.max.y, b.min.z, b.max.z);
    std::printf("thickness: %s\n", model.thickness.empty() ? ("default " + std::to_string(model.default_thickness)).c_str() : "per point");
    std::printf("transparency: %s\ncolour: %s\n", model.transparency.empty() ? "default" : "per point", model.colors.empty() ? "default" : "per point");
    return 0;
}
} // namespace

command add_info_command(CLI::App& app, map_options& o) {
    auto* cmd = app.add_subcommand("info", "print a model's strand, point and segment counts and its bounds");
    add_model(cmd, o);
    return {cmd, [&o] { return run_info(o); }};
}

} // namespace cli
