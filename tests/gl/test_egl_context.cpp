// The EGL context (a GPU's device platform, else Mesa's surfaceless one; llvmpipe on this machine).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <hairshadow/gl/context/egl_context.hpp>

#include <catch2/catch.hpp>

using namespace hairshadow;

TEST_CASE("EGL gives a core context without a display", "[gl][egl]") {
    gl::egl_context ctx(4, 5);
    REQUIRE(gladLoadGL(ctx.loader()) != 0);
    CHECK(gl::gl_version() >= 45);
    CHECK_THAT(ctx.description(), Catch::Contains("OpenGL"));
}
