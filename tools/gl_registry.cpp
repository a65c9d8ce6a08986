// The GL registry (make_gl_shadow_map), compiled once for the project's own programs, as registry.cpp
// compiles the CPU one. The GL headers come after the GL loader.
#include <glad/gl.h>

#define HAIRSHADOW_GL_REGISTRY_IMPLEMENTATION
#include <hairshadow/gl/maps/registry.hpp>
