// `hairshadow export`: a model's shadow maps as OpenEXR images (README, Deep OpenEXR): the exact
// (dsm) or compressed (dsm:EPS) deep shadow map as point and volume samples, any other method's
// optical depth sampled at --samples depths as volume samples (both deep scanline images, which
// `compare --reference` reads back), or with --flat a method's stored maps as a tiled flat image.
#include "command_line.hpp"

#include <hairshadow/io/deep_exr.hpp>
#include <hairshadow/io/flat_exr.hpp>

#include <cstdio>

namespace cli {

using namespace hairshadow;

namespace {
struct export_options {
    std::string out;
    bool flat = false;
    int samples = 64;
};

/// The exact or compressed deep shadow map, as write_deep_exr writes them.
void export_reference(const method_spec& spec, any_shadow_map& map, const std::string& out, int res) {
    if (const auto* compressed = map.method_if<compressed_deep_shadow_map>(); compressed && !spec.fields.empty()) {
        write_deep_exr(out, *compressed, spec.text);
        std::printf("%s: %s at %dx%d, %zu vertices as point and volume samples\n", out.c_str(), spec.text.c_str(), res, res, compressed->vertex_count());
    } else if (const auto* exact = map.method_if<deep_shadow_map>()) {
        write_deep_exr(out, *exact, spec.text);
        std::printf("%s: %s at %dx%d, %zu fragments as point samples\n", out.c_str(), spec.text.c_str(), res, res, exact->fragment_count());
    } else {
        throw error("export: the map of '" + spec.text + "' is not a deep shadow map");
    }
}

int run_export(const map_options& o, const export_options& e) {
    const auto spec = parse_method(o.method);
    check_resolution(o.resolution);
    if (e.flat && names_exact_reference(spec))
        throw usage_error("export: '" + spec.text + "' stores no flat maps (its samples are per fragment); export it without --flat, as a deep image");
    const auto s = prepare_scene(o, false);
    const auto map = build_map(spec, s);
    if (e.flat) {
        if (map->stored_maps() == 0)
            throw usage_error("export: '" + spec.text + "' stores no maps per texel (a fixed fibre density); export it without --flat, as deep samples");
        write_flat_exr(e.out, *map);
        std::printf("%s: %s at %dx%d, %d stored maps as FLOAT channels map*.optical_depth, tiled\n", e.out.c_str(), spec.text.c_str(), o.resolution,
                    o.resolution, map->stored_maps());
    } else if (names_exact_reference(spec)) {
        export_reference(spec, *map, e.out, o.resolution);
    } else {
        write_sampled_deep_exr(e.out, *map, e.samples);
        std::printf("%s: %s at %dx%d, its optical depth at %d + 1 depths a texel as volume samples\n", e.out.c_str(), spec.text.c_str(), o.resolution,
                    o.resolution, e.samples);
    }
    return 0;
}
} // namespace

command add_export_command(CLI::App& app, map_options& o) {
    auto e = std::make_shared<export_options>();
    auto* cmd = app.add_subcommand("export", "write a method's maps as an OpenEXR image: deep samples (dsm, dsm:EPS: the exact or compressed map; "
                                             "any other method: its transmittance sampled in depth), or with --flat its stored maps");
    add_model(cmd, o);
    add_map_options(cmd, o);
    cmd->add_option("--out", e->out, "the OpenEXR file to write: deep scanline (Z: the light's linear depth, A: alpha), or tiled with --flat "
                                     "(see README, Deep OpenEXR)")
        ->required();
    cmd->add_flag("--flat", e->flat, "write the method's stored maps, one FLOAT channel mapKK.optical_depth each, as a tiled flat image");
    cmd->add_option("--samples", e->samples, "for methods other than dsm: the uniform depth intervals over [0, 1] each texel's optical depth is "
                                             "sampled in, 1 to 65536")
        ->check(CLI::Range(1, 65536))
        ->capture_default_str();
    return {cmd, [&o, e] { return run_export(o, *e); }};
}

} // namespace cli
