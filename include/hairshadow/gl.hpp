#pragma once
/// @file
/// The GL back end's umbrella header: gl::maps<Method> (the GL twin of any shadow_method, built by
/// the papers' passes, with its GLSL look-up hs_transmittance), the hair mesh, point queries, errors
/// and RAII objects. Include a GL 4.3+ loader such as glad's <glad/gl.h> first. The headless contexts
/// are separate: <hairshadow/gl/osmesa_context.hpp> and <hairshadow/gl/egl_context.hpp> (after
/// <EGL/egl.h> and <EGL/eglext.h>); run-time method specs: <hairshadow/gl/registry.hpp>.

#include <hairshadow/gl/context.hpp>
#include <hairshadow/gl/error.hpp>
#include <hairshadow/gl/hair_mesh.hpp>
#include <hairshadow/gl/maps.hpp>
#include <hairshadow/gl/objects.hpp>
#include <hairshadow/gl/point_queries.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
