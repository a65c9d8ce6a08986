// `hairshadow render`: the shaded hair from a camera, or the light's view of the transmittance
// behind the model (and each stored map), as PNGs.
#include "command_line.hpp"
#include "scene_setup.hpp"

#include <hairshadow/io/png.hpp>

#include <cstdio>
#include <filesystem>

namespace cli {

using namespace hairshadow;

namespace {
/// What `render` draws beyond the maps: the camera's shaded view (the default) or the light's.
struct render_view {
    std::string view = "camera";
    std::string mesh;
    std::vector<std::string> fill_lights;
    float azimuth = 25.0f, elevation = 10.0f;
    int size = 512;
    std::string transparency = "none";
    float hair_opacity = 0.4f;
    std::string out_path = "transmittance.png";
    std::string maps_dir;
    std::string camera_only; ///< the first camera-view option given, if any
};

/// Every usage error of the camera view, before any work.
void check_shaded(const map_options& o, const render_view& v) {
    check_resolution(o.resolution);
    camera::check_image_size(v.size, v.size);
    check_model_spec(o.model);
    if (o.on_gl() && o.wide > 0.0f) throw usage_error("--wide needs --backend cpu: core GL draws lines one pixel wide");
    if (!o.on_gl() && !o.gl_path.empty()) throw usage_error("--gl-path chooses how --backend gl builds; add --backend gl");
    if (parse_transparency(v.transparency) != transparency::none && v.size > 4096)
        throw usage_error("--transparency needs --size up to 4096");
}

/// Each light's maps and the mesh's depth map on the CPU, then the picture.
image render_on_cpu(const map_options& o, const render_view& v, const method_spec& spec, const hairshadow::scene& sc, const camera& cam,
                    std::span<const light_space> spaces, const raster_options& ro) {
    std::vector<std::unique_ptr<any_shadow_map>> maps;
    std::vector<lit_light> lit;
    for (std::size_t i = 0; i < spaces.size(); ++i) {
        const auto n = std::to_string(i + 1);
        maps.push_back(make_shadow_map(spec));
        step("light " + n + ": building " + spec.text + " from the hair", [&] { maps.back()->build(sc.hair, spaces[i], ro); });
        auto mesh_map = step("light " + n + ": the mesh's depth map", [&] { return depth_shadow_map(sc.mesh, spaces[i], default_mesh_bias, o.exec()); });
        lit.push_back({sc.lights[i], query_of(*maps.back(), o.exec()), std::move(mesh_map)});
    }
    render_options options;
    options.exec = o.exec();
    return step("rendering (transparency " + v.transparency + ")",
                [&] { return render_transparent(sc, cam, lit, parse_transparency(v.transparency), v.hair_opacity, options); });
}

/// The shaded scene from the camera: Kajiya-Kay hair and the mesh, each light with the method's
/// maps (built on the chosen back end) and the mesh's depth map.
int run_shaded(const map_options& o, const render_view& v) {
    const auto spec = parse_method_for(o.method, o);
    std::vector<light_spec> lights{parse_light(o.light)};
    for (const auto& l : v.fill_lights) lights.push_back(parse_light(l));
    check_shaded(o, v);
    std::fprintf(stderr, "render of %s with %s, %zu light(s), on the %s\n", o.model.c_str(), spec.text.c_str(), lights.size(), o.backend.c_str());
    const hairshadow::scene sc = load_scene(o.model, v.mesh, lights);
    const auto cam = camera::framing(sc.bounds(), v.azimuth, v.elevation, v.size, v.size, 1.15f);
    raster_options ro;
    ro.exec = o.exec();
    ro.fixed_alpha = o.alpha;
    ro.wide_line_width = o.wide;
    std::vector<light_space> spaces;
    for (const auto& l : sc.lights) spaces.push_back(light_space::fit(l.spec, sc.bounds(), o.resolution));
    image picture;
    if (o.on_gl()) {
        const auto mode = parse_transparency(v.transparency);
        const auto gl = gl_backend::open(o.context, o.gl_path);
        picture = step("building the maps and rendering on GL (transparency " + v.transparency + ")",
                       [&] { return gl->render_scene(sc, cam, spec, spaces, ro, mode, v.hair_opacity); });
        if (mode == transparency::exact) std::fprintf(stderr, "depth peeling: %d layers\n", gl->peeled_layers());
    } else {
        picture = render_on_cpu(o, v, spec, sc, cam, spaces, ro);
    }
    write_png(v.out_path, picture.width, picture.height, 3, picture.to_srgb8());
    std::fprintf(stderr, "wrote %s (%dx%d)\n", v.out_path.c_str(), picture.width, picture.height);
    return 0;
}

/// The light's view: the transmittance behind the whole model (depth 1), and each stored map.
int run_light_view(const map_options& o, const render_view& v) {
    if (!v.camera_only.empty()) throw usage_error(v.camera_only + " needs --view camera");
    const auto spec = parse_method_for(o.method, o);
    auto s = prepare_scene(o, false);
    std::unique_ptr<any_shadow_map> map;
    if (s.gl) {
        s.gl->build(spec, s.light, s.raster);
        map = s.gl->to_cpu(); // the maps GL built, read back
    } else {
        map = build_map(spec, s);
    }
    const int res = o.resolution;
    write_grey(v.out_path, res, o.exec(), [&](int x, int y) { return map->transmittance(x, y, 1.0f); });
    std::fprintf(stderr, "wrote %s (%dx%d, %s)\n", v.out_path.c_str(), res, res, spec.text.c_str());
    if (v.maps_dir.empty()) return 0;
    std::filesystem::create_directories(v.maps_dir);
    for (int k = 0; k < map->stored_maps(); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "map_%03d.png", k);
        write_grey((std::filesystem::path(v.maps_dir) / name).string(), res, o.exec(),
                   [&](int x, int y) { return std::exp(-map->stored_optical_depth(x, y, k)); });
    }
    std::fprintf(stderr, "wrote %d stored maps to %s\n", map->stored_maps(), v.maps_dir.c_str());
    return 0;
}

int run_render(const map_options& o, render_view& v, const CLI::App& cmd) {
    for (const char* name : {"--mesh", "--fill-light", "--azimuth", "--elevation", "--size", "--transparency", "--hair-opacity"})
        if (cmd.count(name) > 0 && v.camera_only.empty()) v.camera_only = name;
    if (v.view == "light") return run_light_view(o, v);
    if (!v.maps_dir.empty()) throw usage_error("--maps needs --view light");
    return run_shaded(o, v);
}
} // namespace

command add_render_command(CLI::App& app, map_options& o) {
    auto v = std::make_shared<render_view>();
    auto* cmd = app.add_subcommand("render", "write the shaded hair (or the light's view of its transmittance) as a PNG");
    add_model(cmd, o);
    add_map_options(cmd, o);
    add_backend_options(cmd, o);
    cmd->add_option("--out", v->out_path, "output PNG");
    cmd->add_option("--view", v->view, "camera: the shaded scene; light: the transmittance behind the model, from the light")
        ->check(CLI::IsMember({"camera", "light"}));
    cmd->add_option("--mesh", v->mesh, "an OBJ whose faces are the opaque mesh (procedural models stand on their sphere)");
    cmd->add_option("--fill-light", v->fill_lights, "another light, dimmer, with its own maps (repeatable)");
    cmd->add_option("--azimuth", v->azimuth, "camera azimuth in degrees about +y")->check(finite_number);
    cmd->add_option("--elevation", v->elevation, "camera elevation in degrees")->check(finite_number & CLI::Range(-89.0f, 89.0f));
    cmd->add_option("--size", v->size, "image size in pixels")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    cmd->add_option("--transparency", v->transparency,
                    "none (opaque hair), occupancy (Sintorn & Assarsson 3.4), weighted (Bavoil & Myers), exact (sorted)")
        ->check(CLI::IsMember({"none", "occupancy", "weighted", "exact"}));
    cmd->add_option("--hair-opacity", v->hair_opacity, "each strand's alpha over a pixel it covers, with --transparency")
        ->check(finite_number & CLI::Range(0.001f, 1.0f));
    cmd->add_option("--maps", v->maps_dir, "with --view light: also write each stored map (layer, bin or slab) as a PNG into this folder");
    return {cmd, [&o, v, cmd] { return run_render(o, *v, *cmd); }};
}

} // namespace cli
