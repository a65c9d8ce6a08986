#pragma once
/// @file
/// The GL back end's umbrella header: gl::maps<Method> (the GL twin of any shadow_method, built by
/// the papers' passes, with its GLSL look-up hs_transmittance), the light pass several methods share,
/// the hair mesh, point queries, errors and RAII objects. Include a GL 4.3+ loader such as glad's
/// <glad/gl.h> first (or any header declaring the GL 4.3 functions). The headless contexts are
/// separate: <hairshadow/gl/context/osmesa_context.hpp> and <hairshadow/gl/context/egl_context.hpp> (after
/// <EGL/egl.h> and <EGL/eglext.h>); run-time method specs: <hairshadow/gl/maps/registry.hpp>.
///
/// The state contract, for use inside someone else's renderer (README, "The GL state contract"):
/// - light_pass::run, maps.build, maps.read_back, point_queries::run and the hair_mesh constructor
///   restore every piece of GL state they change (gl/context/state_guard.hpp lists it), also when they throw;
/// - they set the state their passes need (no scissor, blending, depth or stencil test, culling,
///   logic op or rasteriser discard; full colour masks; their own viewport, framebuffers, program,
///   vertex array, textures and no sampler objects), whatever the caller left;
/// - errors the caller left unread are read first, so they neither fail a build nor pass for the
///   library's own, and raised again on the way out for the caller to read; the library's own are
///   thrown as gl_error naming the pass. Each call's GL commands are in a KHR_debug group named
///   "hairshadow: ...";
/// - bind_lookup(program, first_unit, prefix, depth_bias) sets uniforms with glProgramUniform (the
///   program need not be current) and binds Maps::texture_units textures from first_unit, with no
///   sampler objects; it leaves the active texture unit as found, and throws argument_error naming
///   a uniform the program lacks. lookup_source(prefix) renames every name so that look-ups with
///   different prefixes share one shader;
/// - no build reads anything back: the depth extent is reduced on the GPU. Framebuffers and programs
///   are made once per object and reused by every build.

#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/context/error.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>
#include <hairshadow/gl/passes/light_pass.hpp>
#include <hairshadow/gl/lookup/lookup_binding.hpp>
#include <hairshadow/gl/maps/maps.hpp>
#include <hairshadow/gl/context/objects.hpp>
#include <hairshadow/gl/lookup/point_queries.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/gl/context/state_guard.hpp>
