#pragma once
// One OSMesa core 4.5 context for all GL tests of the executable, current and loaded.
#include <glad/gl.h>

#include <hairshadow/gl/osmesa_context.hpp>

#include <catch2/catch.hpp>

namespace test {
inline hairshadow::gl::osmesa_context& gl_context() {
    static hairshadow::gl::osmesa_context ctx(4, 5);
    static const bool loaded = gladLoadGL(ctx.loader()) != 0;
    REQUIRE(loaded);
    ctx.make_current();
    return ctx;
}
} // namespace test
