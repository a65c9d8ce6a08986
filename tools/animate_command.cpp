// The animation of Yuksel & Keyser's claim (section 1: layering artifacts "are especially significant
// in animated sequences"): every method and the exact reference rebuilt each frame from swaying hair
// and an orbiting light, rendered side by side, and measured over time: the mean error and the flicker
// at every hair point (reference/temporal_error.hpp).
#include "animate.hpp"
#include "command_line.hpp"

#include "compare_table.hpp"
#include "panel_grid.hpp"
#include "progress.hpp"
#include "scene_setup.hpp"

#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/png.hpp>
#include <hairshadow/methods/registry.hpp>
#include <hairshadow/procedural/motion.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>

#include <unistd.h>

namespace cli {
namespace {

using namespace hairshadow;
namespace fs = std::filesystem;

/// One panel: a method, its maps (reused every frame) and what it measured.
struct track {
    std::string spec, label;
    std::unique_ptr<any_shadow_map> map;
    std::vector<double> rebuild_ms; ///< every frame after the first
    double cold_ms = 0;
    temporal_error errors;
};

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// The ffmpeg on the PATH, or "" where there is none.
std::string find_ffmpeg() {
    const char* path = std::getenv("PATH");
    if (!path) return "";
    for (auto dir : detail::split(path, ':')) {
        const fs::path candidate = fs::path(std::string(dir)) / "ffmpeg";
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return "";
}

/// `text` as one word of a POSIX shell command: in single quotes, each quote in it closed, escaped
/// and reopened.
std::string shell_word(const std::string& text) {
    std::string out = "'";
    for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

/// Frames piped into ffmpeg as raw RGB, encoded as H.264 in an MP4 (padded to even sizes, as yuv420p
/// needs). A failing ffmpeg costs the MP4, never the run: SIGPIPE is ignored while it is open.
class mp4_pipe {
public:
    mp4_pipe(const std::string& ffmpeg, const fs::path& out, int width, int height, int fps) {
        std::ostringstream cmd;
        cmd << shell_word(ffmpeg) << " -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " << width << "x" << height << " -r " << fps
            << " -i - -vf " << shell_word("pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white") << " -pix_fmt yuv420p -c:v libx264 "
            << shell_word("file:" + out.string()); // file: so that no path reads as an option
        previous_ = std::signal(SIGPIPE, SIG_IGN);
        pipe_ = popen(cmd.str().c_str(), "w");
        if (!pipe_) {
            std::signal(SIGPIPE, previous_);
            throw io_error(out.string(), "cannot start ffmpeg");
        }
    }
    mp4_pipe(const mp4_pipe&) = delete;
    mp4_pipe& operator=(const mp4_pipe&) = delete;
    ~mp4_pipe() {
        if (pipe_) pclose(pipe_);
        std::signal(SIGPIPE, previous_);
    }
    void add(const std::vector<std::uint8_t>& rgb) { ok_ = ok_ && std::fwrite(rgb.data(), 1, rgb.size(), pipe_) == rgb.size(); }
    /// True when every frame went through and ffmpeg wrote the file.
    bool finish() {
        const int status = pclose(pipe_);
        pipe_ = nullptr;
        return ok_ && status == 0;
    }

private:
    FILE* pipe_ = nullptr;
    bool ok_ = true;
    void (*previous_)(int) = SIG_DFL;
};

/// animate.md and animate.csv: each method's error, flicker and rebuild times, after what was measured.
void write_animate_table(const animate_options& o, const std::vector<track>& tracks, std::size_t points, const std::string& credit) {
    std::ostringstream md, csv;
    md << "Model `" << o.model << "`" << (o.mesh.empty() ? "" : ", mesh `" + o.mesh + "`") << ", " << o.frames << " frames at " << o.fps
       << " fps, motion `" << (o.motion == motion_kind::sway ? "sway" : o.motion == motion_kind::light ? "light" : "both") << "` (sway up to "
       << o.amplitude << " degrees at the tips, seed " << o.seed << "; the light `" << o.light << "` orbiting once), maps " << o.resolution << "x"
       << o.resolution << ", " << points << " points, " << o.exec.resolved()
       << " threads. Errors are e = T - T_exact at every hair point of every frame; flicker is |e(t+1) - e(t)| over consecutive frames "
          "(the last to the first too: the animation loops); times are CPU rebuilds straight from the moved model."
       << (credit.empty() ? "" : " " + credit + ".") << "\n\n"
       << "| method | mean error | flicker | flicker / mean error | rebuild median (ms) | rebuild min-max (ms) | cold build (ms) |\n"
       << "|---|---|---|---|---|---|---|\n";
    csv << "method,mean_error,flicker,rebuild_median_ms,rebuild_min_ms,rebuild_max_ms,cold_ms\n";
    char line[512];
    for (const auto& tr : tracks) {
        const double mean = tr.errors.mean_error(), flicker = tr.errors.flicker();
        const double lo = tr.rebuild_ms.empty() ? 0 : *std::min_element(tr.rebuild_ms.begin(), tr.rebuild_ms.end());
        const double hi = tr.rebuild_ms.empty() ? 0 : *std::max_element(tr.rebuild_ms.begin(), tr.rebuild_ms.end());
        char ratio[32] = "-";
        if (mean > 0) std::snprintf(ratio, sizeof ratio, "%.2f", flicker / mean);
        std::snprintf(line, sizeof line, "| %s | %.4f | %.4f | %s | %.1f | %.1f-%.1f | %.1f |\n", tr.spec.c_str(), mean, flicker, ratio,
                      median(tr.rebuild_ms), lo, hi, tr.cold_ms);
        md << line;
        std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%.3f,%.3f,%.3f,%.3f\n", tr.spec.c_str(), mean, flicker, median(tr.rebuild_ms), lo, hi, tr.cold_ms);
        csv << line;
    }
    write_file(fs::path(o.out) / "animate.md", md.str());
    write_file(fs::path(o.out) / "animate.csv", csv.str());
    std::fputs(md.str().c_str(), stdout);
}

} // namespace

int run_animate(const animate_options& o) {
    std::fprintf(stderr, "animation of %s, %d frames\n", o.model.c_str(), o.frames);
    const std::string credit = credit_for(o.model, o.mesh);
    const light_spec light0 = parse_light_spec(o.light);
    scene sc = load_scene(o.model, o.mesh, {light0});
    const bool sways = o.motion != motion_kind::light, orbits = o.motion != motion_kind::sway;
    const float duration = float(o.frames) / float(o.fps);
    const auto time_of = [&](int frame) { return float(frame) / float(o.fps); };
    // The sway and the orbit each take the whole animation, so that it loops without a jump.
    const sway_motion sway(sc.hair, {.amplitude_degrees = sways ? o.amplitude : 0.0f, .period = duration, .seed = o.seed});
    const glm::vec3 centre = sc.bounds().center();
    const auto light_at = [&](float t) { return orbits ? orbit_light(light0, t, duration, centre) : light0; };

    // One box for every frame: the maps' frustum and the camera stay still while the hair moves. The
    // maps hold the mesh too (it shadows the hair); the camera frames the hair.
    aabb hair_box = sc.hair.bounds();
    hair_model posed;
    for (int f = 0; sways && f < o.frames; ++f) {
        sway.pose(time_of(f), posed, o.exec);
        const aabb b = posed.bounds();
        hair_box.add(b.min);
        hair_box.add(b.max);
    }
    aabb box = sc.bounds();
    box.add(hair_box.min);
    box.add(hair_box.max);
    std::vector<track> tracks;
    for (auto part : detail::split(o.methods, ',')) tracks.push_back({std::string(part), pretty(std::string(part)), nullptr, {}, 0, {}});
    tracks.push_back({"dsm", "exact (DSM)", nullptr, {}, 0, {}});
    for (auto& t : tracks) t.map = make_shadow_map(t.spec); // throws spec_error for a bad spec, before any work
    const track& exact = tracks.back();

    const auto cam = camera::framing(hair_box, o.azimuth, o.elevation, o.size, o.size, 1.1f);
    render_options ro;
    ro.exec = o.exec;
    ro.supersample = o.supersample;
    raster_options raster;
    raster.exec = o.exec;

    fs::create_directories(o.out);
    std::unique_ptr<apng_writer> apng;
    std::unique_ptr<mp4_pipe> mp4;
    const std::string ffmpeg = find_ffmpeg();
    const std::size_t points = sc.hair.point_count();
    std::vector<float> reference(points), t_method(points);
    const int columns = int(tracks.size());
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < o.frames; ++f) {
        const float t = time_of(f);
        if (sways) sway.pose(t, sc.hair, o.exec);
        sc.lights[0].spec = light_at(t);
        const auto space = light_space::fit(sc.lights[0].spec, box, o.resolution);
        for (auto& tr : tracks) {
            const auto begin = std::chrono::steady_clock::now();
            tr.map->build(sc.hair, space, raster);
            const double ms = ms_since(begin);
            if (f == 0) tr.cold_ms = ms; // the first build allocates the maps and the working memory
            else tr.rebuild_ms.push_back(ms);
        }
        exact.map->transmittance(sc.hair.points, reference, {}, o.exec);
        for (auto& tr : tracks) {
            tr.map->transmittance(sc.hair.points, t_method, {}, o.exec);
            tr.errors.add_frame(t_method, reference);
        }
        // The frame: every method's render, side by side.
        const depth_shadow_map mesh_shadow(sc.mesh, space, default_mesh_bias, o.exec);
        std::vector<image> cells;
        std::vector<std::string> labels;
        for (const auto& tr : tracks) {
            const std::vector<lit_light> lights{{sc.lights[0], query_of(*tr.map, o.exec), mesh_shadow}};
            cells.push_back(render_cpu(sc, cam, lights, ro));
            labels.push_back(tr.label);
        }
        const image frame = grid(cells, labels, columns, credit);
        const auto rgb = frame.to_srgb8();
        if (!apng) {
            apng = std::make_unique<apng_writer>((fs::path(o.out) / "animate.png").string(), frame.width, frame.height, 3, o.frames,
                                                 std::uint16_t(1), std::uint16_t(o.fps),
                                                 o.full_colour ? png_colours::full : png_colours::palette);
            if (!ffmpeg.empty()) mp4 = std::make_unique<mp4_pipe>(ffmpeg, fs::path(o.out) / "animate.mp4", frame.width, frame.height, o.fps);
        }
        apng->add_frame(rgb);
        if (mp4) mp4->add(rgb);
        std::fprintf(stderr, "  frame %d of %d (%.0f ms so far)\n", f + 1, o.frames, ms_since(start));
    }
    apng->finish();
    std::fprintf(stderr, "wrote %s\n", (fs::path(o.out) / "animate.png").string().c_str());
    if (mp4) {
        if (mp4->finish()) std::fprintf(stderr, "wrote %s\n", (fs::path(o.out) / "animate.mp4").string().c_str());
        else std::fprintf(stderr, "note: ffmpeg could not write animate.mp4\n");
    } else {
        std::fprintf(stderr, "note: no ffmpeg on the PATH, so no animate.mp4 (apt-get install ffmpeg)\n");
    }

    write_animate_table(o, tracks, points, credit);
    return 0;
}

namespace {
struct animate_args {
    animate_options options;
    std::string motion = "both";
};

int run_animate_command(const map_options& o, animate_args& a) {
    try { // everything a usage error can be, before any work
        hairshadow::check_resolution(a.options.resolution);
    } catch (const hairshadow::argument_error& e) {
        throw usage_error(e.what());
    }
    check_model_spec(a.options.model);
    check_method_list(a.options.methods);
    parse_light(a.options.light);
    a.options.motion = a.motion == "sway" ? motion_kind::sway : a.motion == "light" ? motion_kind::light : motion_kind::both;
    a.options.exec = o.exec();
    return run_animate(a.options);
}
} // namespace

command add_animate_command(CLI::App& app, map_options& o) {
    auto a = std::make_shared<animate_args>();
    auto& anim = a->options;
    auto* cmd = app.add_subcommand("animate", "the methods side by side over frames of swaying hair and an orbiting light: "
                                              "an animated PNG (and MP4 with ffmpeg) and a table of error and flicker over time");
    cmd->add_option("MODEL", anim.model, "a .hair, .tfx, .data or .obj file, or " + std::string(hairshadow::procedural_grammar))->required();
    cmd->add_option("--mesh", anim.mesh, "an OBJ whose faces are the opaque mesh (e.g. the Sintel head)");
    cmd->add_option("--light", anim.light, "the light at the first frame: " + std::string(hairshadow::light_grammar));
    cmd->add_option("--methods", anim.methods, "comma-separated method specs; the exact reference is always the last panel")->capture_default_str();
    cmd->add_option("--frames", anim.frames, "frames, 1 to 1000")->check(CLI::Range(1, 1000));
    cmd->add_option("--fps", anim.fps, "frames per second, 1 to 100")->check(CLI::Range(1, 100));
    cmd->add_option("--motion", a->motion, "sway (the hair), light (an orbit) or both")->check(CLI::IsMember({"sway", "light", "both"}));
    cmd->add_option("--amplitude", anim.amplitude, "the sway's largest turn of a strand's tip, 0 to 90 degrees")
        ->check(finite_number & CLI::Range(0.0f, 90.0f));
    cmd->add_option("--seed", anim.seed, "the sway's seed");
    cmd->add_option("--res", anim.resolution, "shadow map resolution")->check(CLI::Range(1, HAIRSHADOW_MAX_RESOLUTION));
    cmd->add_option("--size", anim.size, "panel size in pixels, 16 to 1024")->check(CLI::Range(16, 1024));
    cmd->add_option("--supersample", anim.supersample, "render each panel at N x N samples a pixel, 1 to 4")->check(CLI::Range(1, 4));
    cmd->add_option("--azimuth", anim.azimuth, "camera azimuth in degrees about +y")->check(finite_number);
    cmd->add_option("--elevation", anim.elevation, "camera elevation in degrees")->check(finite_number & CLI::Range(-89.0f, 89.0f));
    cmd->add_option("--out", anim.out, "output folder");
    cmd->add_flag("--full-colour", anim.full_colour, "write the animated PNG in full colour, not in one 256-colour palette (a larger file)");
    return {cmd, [&o, a] { return run_animate_command(o, *a); }};
}

} // namespace cli
