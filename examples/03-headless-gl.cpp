// 03-headless-gl: shaded hair rendered on the GPU with no window. A headless EGL context (a GPU
// through EGL's device platform, else Mesa's llvmpipe), deep opacity maps built by their two GL
// passes, and the GL renderer drawing the hair on its sphere with Kajiya-Kay shading; writes a PNG.
//
//   03-headless-gl [OUT.png]
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <hairshadow/gl.hpp>
#include <hairshadow/gl/context/egl_context.hpp>
#include <hairshadow/gl/render/scene_renderer.hpp>
#include <hairshadow/hairshadow.hpp>
#include <hairshadow/io/png.hpp>

#include <cstdio>

int main(int argc, char** argv) try {
    using namespace hairshadow;
    const std::string out = argc > 1 ? argv[1] : "headless.png";
    gl::egl_context context(4, 3);
    if (!gladLoadGL(context.loader())) throw gl::gl_error("cannot load GL");
    std::printf("%s\n", context.description().c_str());

    scene sc;
    sc.hair = make_procedural({.style = hair_style::curly, .strands = 4000, .segments = 24});
    sc.mesh = make_sphere({0, 0, 0}, 0.1f, 48);
    sc.lights = {{light_spec::directional({-0.7f, -0.9f, -0.45f}), glm::vec3(1.1f)}};
    const auto light = light_space::fit(sc.lights[0].spec, sc.bounds(), 512);

    const gl::hair_mesh strands(sc.hair);
    gl::maps<deep_opacity_maps<3>> dom; // Yuksel & Keyser 2008: a depth pass, then one additive pass
    dom.build(strands, light);
    gl::scene_renderer renderer(sc);
    renderer.add_light(sc.lights[0], dom);
    const image picture = renderer.render(camera::framing(sc.bounds(), 25.0f, 10.0f, 512, 512, 1.15f));
    write_png(out, picture.width, picture.height, 3, picture.to_srgb8());
    std::printf("wrote %s\n", out.c_str());
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
