#pragma once
/// @file
/// The GL back end's umbrella header (groundwork: errors, RAII objects, embedded shader snippets).
/// Include a GL 4.3+ loader such as glad's <glad/gl.h> first. The headless contexts are separate:
/// <hairshadow/gl/osmesa_context.hpp> (after <GL/osmesa.h>'s prerequisites) and
/// <hairshadow/gl/egl_context.hpp> (after <EGL/egl.h> and <EGL/eglext.h>).

#include <hairshadow/gl/context.hpp>
#include <hairshadow/gl/error.hpp>
#include <hairshadow/gl/objects.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
