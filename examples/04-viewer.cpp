// An interactive viewer: the hair on its mesh, lit by one light whose shadows come from any method,
// built on the GPU every time something changes.
//
//   04-viewer [MODEL] [--mesh OBJ] [--transparency MODE] [--sway] [--frames N] [--screenshot FILE.png]
//
// Drag with the left mouse button (or the arrow keys) to orbit the camera, WASD to move the light,
// keys 1-9 and 0 to switch methods (no hair shadows, OSM, DOM, DC, OCC, deep occupancy, TressFX's approximate
// deep shadow maps, Unreal Engine's hair-count deep shadows, Fourier opacity maps, moment shadow maps; V for adaptive volumetric
// shadow maps; the exact reference is CPU-only), [ and ] to halve or double the layer count, T to cycle the hair's transparency (opaque,
// occupancy-ordered, weighted averages, exact by depth peeling), - and = to change the hair's
// opacity, M to let the hair sway in the wind (its maps then rebuilt every frame), Esc to quit. The
// title shows the method, its GL build time, the transparency and the frame rate. --frames N draws N frames and exits (tests run it under Xvfb); --screenshot writes the
// last one.
#include <glad/gl.h>

#include <GLFW/glfw3.h>

#include <hairshadow/gl/maps/registry.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/obj_format.hpp>
#include <hairshadow/io/png.hpp>
#include <hairshadow/procedural/motion.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <cstring>
#include <string>

using namespace hairshadow;

namespace {

struct state {
    int family = 2; // 1 none, 2 OSM, 3 DOM, 4 DC, 5 OCC, 6 deep occupancy (hybrid), 7 ADSM, 8 Unreal, 9 FOM, 10 MSM, 11 AVSM
    int layers = 16;
    float azimuth = 25, elevation = 10;
    float light_azimuth = -60, light_elevation = 50;
    transparency hair = transparency::none;
    float hair_opacity = 0.4f;
    bool dirty = true;
    bool sway = false; // the hair moves: new points and maps every frame
    bool dragging = false;
    double last_x = 0, last_y = 0;
};

std::string spec_of(const state& s) {
    switch (s.family) {
    case 2: return "osm:" + std::to_string(s.layers);
    case 3: return "dom:" + std::to_string(std::clamp(s.layers, 1, 8));
    case 4: return "dc:" + std::to_string(std::clamp(s.layers, 1, 8));
    case 5: return "occ:" + std::to_string(std::clamp(s.layers, 32, 256)) + ":4";
    case 6: return "docc:" + std::to_string(std::clamp(s.layers, 32, 256)) + ":4";
    case 7: return "adsm";
    case 8: return "ue:" + std::to_string(s.layers <= 2 ? 2 : s.layers <= 4 ? 4 : 8);
    case 9: return "fom:" + std::to_string(s.layers <= 2 ? 3 : s.layers <= 4 ? 5 : s.layers <= 8 ? 7 : s.layers <= 16 ? 11 : 15);
    case 10: return "msm";
    case 11: return "avsm:" + std::to_string(s.layers <= 4 ? 4 : s.layers <= 8 ? 8 : 16);
    default: return "none";
    }
}

glm::vec3 light_direction(const state& s) {
    const float az = glm::radians(s.light_azimuth), el = glm::radians(s.light_elevation);
    return -glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)); // travels towards the model
}

void on_key(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    auto& s = *static_cast<state*>(glfwGetWindowUserPointer(window));
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, 1);
    if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) s.family = key - GLFW_KEY_0, s.dirty = true;
    if (key == GLFW_KEY_0) s.family = 10, s.dirty = true;
    if (key == GLFW_KEY_V) s.family = 11, s.dirty = true;
    if (key == GLFW_KEY_M) s.sway = !s.sway;
    if (key == GLFW_KEY_T) s.hair = transparency((int(s.hair) + 1) % 4);
    if (key == GLFW_KEY_MINUS) s.hair_opacity = std::max(0.05f, s.hair_opacity - 0.05f);
    if (key == GLFW_KEY_EQUAL) s.hair_opacity = std::min(1.0f, s.hair_opacity + 0.05f);
    if (key == GLFW_KEY_LEFT_BRACKET) s.layers = std::max(1, s.layers / 2), s.dirty = true;
    if (key == GLFW_KEY_RIGHT_BRACKET) s.layers = std::min(512, s.layers * 2), s.dirty = true;
    if (key == GLFW_KEY_LEFT) s.azimuth -= 5;
    if (key == GLFW_KEY_RIGHT) s.azimuth += 5;
    if (key == GLFW_KEY_UP) s.elevation = std::min(80.0f, s.elevation + 5);
    if (key == GLFW_KEY_DOWN) s.elevation = std::max(-80.0f, s.elevation - 5);
    if (key == GLFW_KEY_A) s.light_azimuth -= 10, s.dirty = true;
    if (key == GLFW_KEY_D) s.light_azimuth += 10, s.dirty = true;
    if (key == GLFW_KEY_W) s.light_elevation = std::min(85.0f, s.light_elevation + 10), s.dirty = true;
    if (key == GLFW_KEY_S) s.light_elevation = std::max(-85.0f, s.light_elevation - 10), s.dirty = true;
}

void on_button(GLFWwindow* window, int button, int action, int) {
    auto& s = *static_cast<state*>(glfwGetWindowUserPointer(window));
    if (button == GLFW_MOUSE_BUTTON_LEFT) s.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(window, &s.last_x, &s.last_y);
}

void on_move(GLFWwindow* window, double x, double y) {
    auto& s = *static_cast<state*>(glfwGetWindowUserPointer(window));
    if (s.dragging) {
        s.azimuth -= float(x - s.last_x) * 0.4f;
        s.elevation = std::clamp(s.elevation + float(y - s.last_y) * 0.4f, -80.0f, 80.0f);
    }
    s.last_x = x, s.last_y = y;
}

/// The command line: the model, an optional mesh, a screenshot after a number of frames.
struct viewer_args {
    std::string model = "procedural:wavy:strands=3000", mesh_path, screenshot;
    long frames = -1;
};

/// Reads the command line into `args` and `s`; an exit status where it cannot (2: usage).
std::optional<int> parse_args(int argc, char** argv, viewer_args& args, state& s) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--mesh" && i + 1 < argc) args.mesh_path = argv[++i];
        else if (a == "--frames" && i + 1 < argc) args.frames = std::stol(argv[++i]);
        else if (a == "--screenshot" && i + 1 < argc) args.screenshot = argv[++i];
        else if (a == "--transparency" && i + 1 < argc) {
            try {
                s.hair = parse_transparency(argv[++i]);
            } catch (const argument_error& e) {
                return std::fprintf(stderr, "error: %s\n", e.what()), 2;
            }
        }
        else if (a == "--sway") s.sway = true;
        else if (!a.starts_with("--")) args.model = a;
        else return std::fprintf(stderr, "usage: 04-viewer [MODEL] [--mesh OBJ] [--transparency none|occupancy|weighted|exact] [--sway] [--frames N] [--screenshot FILE.png]\n"), 2;
    }
    return std::nullopt;
}

/// The framebuffer as a PNG, top row first.
void save_screenshot(const std::string& path, int width, int height) {
    std::vector<std::uint8_t> rgba(std::size_t(4 * width * height)), rgb;
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    for (int y = height - 1; y >= 0; --y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) rgb.push_back(rgba[std::size_t(4 * (y * width + x) + c)]);
    write_png(path, width, height, 3, rgb);
}

/// The window's title: the method, its build time, the motion, the hair's transparency, the frame rate.
std::string window_title(const state& s, double build_ms, double fps, int peeled_layers) {
    const std::string hair = s.hair == transparency::none ? "opaque hair"
                             : s.hair == transparency::occupancy ? "occupancy-ordered hair"
                             : s.hair == transparency::weighted ? "weighted-average hair"
                                                                : "exact hair (" + std::to_string(peeled_layers) + " layers peeled)";
    char title[256];
    std::snprintf(title, sizeof title, "hairshadow viewer - %s (1-7 method, [ ] layers) - %s in %.1f ms - %s (M) - %s, opacity %.2f (T, - =) - %.1f fps",
                  spec_of(s).c_str(), s.sway ? "rebuilt every frame" : "built", build_ms, s.sway ? "swaying" : "still", hair.c_str(),
                  s.hair_opacity, fps);
    return title;
}

int run(int argc, char** argv) {
    state s;
    viewer_args args;
    if (const auto status = parse_args(argc, argv, args, s)) return *status;
    const std::string& model = args.model;
    const long frames = args.frames;
    scene sc;
    sc.hair = load_model(model);
    if (!args.mesh_path.empty()) sc.mesh = read_obj(args.mesh_path).mesh;
    else if (is_procedural_spec(model)) sc.mesh = make_sphere({0, 0, 0}, parse_procedural_spec(model).head_radius, 48);

    if (!glfwInit()) return std::fprintf(stderr, "error: GLFW cannot initialise (no display?)\n"), 1;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    const int width = 720, height = 720;
    GLFWwindow* window = glfwCreateWindow(width, height, "hairshadow viewer", nullptr, nullptr);
    if (!window) return glfwTerminate(), std::fprintf(stderr, "error: cannot open a GL 4.3 core window\n"), 1;
    glfwMakeContextCurrent(window);
    if (!gladLoadGL(glfwGetProcAddress)) return std::fprintf(stderr, "error: cannot load GL\n"), 1;
    glfwSetWindowUserPointer(window, &s);
    glfwSetKeyCallback(window, on_key);
    glfwSetMouseButtonCallback(window, on_button);
    glfwSetCursorPosCallback(window, on_move);

    {
        // The wind, and one box for the light's frustum and the camera that holds every pose.
        const sway_motion sway(sc.hair, {.amplitude_degrees = 18.0f, .period = 2.5f});
        aabb box = sc.bounds();
        for (int i = 0; i < 16; ++i) {
            const aabb b = sway.pose(2.5f * float(i) / 16.0f).bounds();
            box.add(b.min), box.add(b.max);
        }
        gl::hair_mesh hair_mesh(sc.hair);
        gl::scene_renderer renderer(sc);
        std::unique_ptr<gl::any_gl_shadow_map> maps;
        light_space space;
        double build_ms = 0, fps = 0;
        bool swaying = false;
        const auto started = std::chrono::steady_clock::now();
        auto last = started;
        for (long frame = 0; !glfwWindowShouldClose(window) && frame != frames; ++frame) {
            if (s.sway || swaying) { // the hair moves (or comes back to rest): new points, then the same maps rebuilt
                if (s.sway) sway.pose(float(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()), sc.hair);
                else sc.hair.points = sway.rest().points; // back to rest
                hair_mesh.update(sc.hair.points);
                renderer.update_hair();
                swaying = s.sway;
                if (maps && !s.dirty) {
                    const auto start = std::chrono::steady_clock::now();
                    maps->build(hair_mesh, space);
                    glFinish();
                    build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                }
            }
            if (s.dirty) { // new method or light: new maps, built on the GPU
                sc.lights = {{light_spec::directional(light_direction(s)), glm::vec3(1.1f)}};
                space = light_space::fit(sc.lights[0].spec, box, 512);
                renderer.clear_lights();
                const auto spec = spec_of(s);
                const auto start = std::chrono::steady_clock::now();
                if (spec == "none") {
                    maps.reset();
                    renderer.add_unshadowed_light(sc.lights[0], space);
                } else {
                    maps = gl::make_gl_shadow_map(parse_method_spec(spec));
                    maps->build(hair_mesh, space);
                    renderer.add_light(sc.lights[0], *maps);
                }
                build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                s.dirty = false;
            }
            int fb_width = 0, fb_height = 0;
            glfwGetFramebufferSize(window, &fb_width, &fb_height);
            const auto cam = camera::framing(box, s.azimuth, s.elevation, std::max(fb_width, 1), std::max(fb_height, 1), 1.15f);
            renderer.set_transparency(s.hair, s.hair_opacity);
            renderer.present(cam, 0);
            if (frame + 1 == frames && !args.screenshot.empty()) save_screenshot(args.screenshot, fb_width, fb_height);
            glfwSwapBuffers(window);
            glfwPollEvents();
            const auto now = std::chrono::steady_clock::now();
            fps = 0.9 * fps + 0.1 / std::max(1e-6, std::chrono::duration<double>(now - last).count());
            last = now;
            glfwSetWindowTitle(window, window_title(s, build_ms, fps, renderer.peeled_layers()).c_str());
        }
        const char* modes[] = {"none", "occupancy", "weighted", "exact"};
        std::printf("%s: %ld frames, last build %.1f ms, transparency %s%s\n", spec_of(s).c_str(), frames, build_ms, modes[int(s.hair)],
                    s.sway ? ", swaying" : "");
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
