// The GL back end with GL's functions from a table of the program's own, as a loader that keeps them
// in a namespace or a table per context gives them (glbinding, glad's MX mode), not from globals: no
// glad here, and no GL prototype. <GL/glcorearb.h> without GL_GLEXT_PROTOTYPES gives the types, enums
// and PFN typedefs; HAIRSHADOW_GL_FUNCTIONS (gl/context/gl_functions.hpp) generates the table and, in
// namespace hairshadow::gl, a reference to each of its pointers under GL's name, which the library's
// unqualified calls find. A call past the list would not compile (no global declaration), and the
// executable links no gl* or glad_* symbol (`nm -u`). Its own executable: in the GL tests' one, the
// library's inline functions would be compiled twice, calling glad there and the table here.
#include <GL/glcorearb.h>

#include <hairshadow/gl/context/gl_functions.hpp>

#include <string>
#include <vector>

namespace own_loader {

/// One context's GL functions: a member per function the library calls, named as GL names it.
struct gl_table {
#define OWN_LOADER_MEMBER(name, type) type name = nullptr;
    HAIRSHADOW_GL_FUNCTIONS(OWN_LOADER_MEMBER)
#undef OWN_LOADER_MEMBER

    /// Fills the table from a context's `get_proc_address`; returns the names it found nothing for.
    template <class GetProcAddress>
    std::vector<std::string> load(GetProcAddress get_proc_address) {
        std::vector<std::string> missing;
#define OWN_LOADER_LOAD(name, type)                                                                                                        \
    name = reinterpret_cast<type>(get_proc_address(#name));                                                                                \
    if (!name) missing.push_back(#name);
        HAIRSHADOW_GL_FUNCTIONS(OWN_LOADER_LOAD)
#undef OWN_LOADER_LOAD
        return missing;
    }
};

/// The table the library calls through: the current context's (a program with several contexts
/// assigns the one it makes current).
inline gl_table current;

} // namespace own_loader

namespace hairshadow::gl {
#define OWN_LOADER_FORWARD(name, type) inline type& name = own_loader::current.name;
HAIRSHADOW_GL_FUNCTIONS(OWN_LOADER_FORWARD)
#undef OWN_LOADER_FORWARD
} // namespace hairshadow::gl

// <GL/osmesa.h> includes <GL/gl.h>, whose GL 1.1 prototypes and types would repeat glcorearb.h's: kept
// out as a GL loader keeps it out (glad does the same), with the calling convention osmesa.h names.
#define __gl_h_
#define GLAPIENTRY APIENTRY
#include <hairshadow/gl/context/osmesa_context.hpp>

#include <hairshadow/gl.hpp>
#include <hairshadow/hairshadow.hpp>

#include "compute_comparison.hpp"

#include <catch2/catch.hpp>

#include <glm/matrix.hpp>

using namespace hairshadow;

namespace {

/// GL's glGetError, counted: the library's error checks reach the table.
int get_error_calls = 0;
PFNGLGETERRORPROC real_get_error = nullptr;
GLenum APIENTRY counted_get_error() {
    ++get_error_calls;
    return real_get_error();
}

} // namespace

TEST_CASE("GL functions from the program's own table, not globals: deep opacity maps equal the CPU's", "[gl][own_loader]") {
    gl::osmesa_context context(4, 5);
    const auto missing = own_loader::current.load(context.loader());
    CAPTURE(missing);
    REQUIRE(missing.empty());
    real_get_error = own_loader::current.glGetError;
    own_loader::current.glGetError = counted_get_error;
    INFO(context.description());
    REQUIRE(gl::compute_path_missing().empty());

    using Method = deep_opacity_maps<3>;
    const auto model = make_procedural({.style = hair_style::curly, .strands = 1000, .segments = 24});
    const auto light = light_space::fit(light_spec::directional({-0.4f, -1.0f, 0.3f}), model.bounds(), 128);
    Method cpu;
    cpu.build(model, light);
    const gl::hair_mesh mesh(model);
    gl::light_pass pass(gl::build_path::compute);
    pass.run(mesh, light);
    gl::maps<Method> on_gl;
    on_gl.build(pass);
    const auto c = test::compare_maps(cpu, on_gl, gl::detail::read_range(*pass.textures()), test::cpu_occupancy(model, light), light.resolution());
    CAPTURE(c.occupied, c.occupied_cpu, c.occupancy_off, c.state_off, c.data_off, c.worst);
    CHECK(c.occupied > 1000);
    CHECK(c.exact());
    CHECK(c.worst <= test::float_tolerance);

    // The GLSL look-up (point queries: a vertex shader writing a storage buffer) against the CPU
    // query of the same maps, at the model's own points.
    const std::vector<glm::vec3> points(model.points.begin(), model.points.end());
    const auto on_gpu = gl::point_queries(on_gl.lookup_source()).run(points, [&](GLuint program) { on_gl.bind_lookup(program); });
    std::vector<float> on_cpu(points.size());
    on_gl.to_cpu().transmittance(points, on_cpu);
    float worst = 0;
    std::size_t shadowed = 0;
    for (std::size_t i = 0; i < points.size(); ++i) worst = std::max(worst, std::abs(on_gpu[i] - on_cpu[i])), shadowed += on_cpu[i] < 0.9f;
    CAPTURE(worst, points.size(), shadowed);
    CHECK(points.size() > 1000);
    CHECK(shadowed * 10 > points.size());
    CHECK(worst <= 1e-5f);
    CHECK(get_error_calls > 0); // the library's checks called glGetError through the table
    own_loader::current.glGetError = real_get_error;
}
