#pragma once
/// @file
/// The GL functions the GL back end calls, as an X-macro: HAIRSHADOW_GL_FUNCTIONS(X) expands to
/// X(glName, PFNGLNAMEPROC) for each, sorted, with the Khronos typedef of its pointer (<GL/glcorearb.h>
/// and glad's <glad/gl.h> both declare it). The EGL and OSMesa calls of the headless contexts
/// (gl/context/egl_context.hpp, osmesa_context.hpp) are not GL's and are not listed. scripts/check_gl_functions.py
/// (a ctest) keeps the list equal to the names the code uses. Where glad's macros are defined, an X
/// macro's `name` expands to glad's pointer (glad_glName); `#name` is always GL's name.
///
/// The library calls each by its bare name from inside namespace hairshadow::gl, never qualified as
/// ::glName, so a call resolves to whatever that name finds there:
/// - a GL loader's globals or macros, included first as usual (glad's <glad/gl.h> makes glName a
///   macro for its pointer glad_glName);
/// - or, for a loader that keeps the functions elsewhere (in a namespace, or a table per context:
///   glbinding, glad's MX mode, one's own), declarations of these names in namespace hairshadow::gl
///   made before the first hairshadow GL header, which hide any global one. From this list:
///
///       #include <GL/glcorearb.h> // types, enums and the PFN typedefs; no GL_GLEXT_PROTOTYPES
///       #include <hairshadow/gl/context/gl_functions.hpp>
///       struct gl_table { // loaded per context from the context's get-proc-address
///       #define MEMBER(name, type) type name = nullptr;
///           HAIRSHADOW_GL_FUNCTIONS(MEMBER)
///       };
///       inline gl_table current_gl; // the current context's: assigned when making a context current
///       namespace hairshadow::gl {
///       #define FORWARD(name, type) inline type& name = current_gl.name;
///       HAIRSHADOW_GL_FUNCTIONS(FORWARD)
///       }
///       #include <hairshadow/gl.hpp>
///
///   tests/gl/test_gl_own_loader.cpp does this, and links no global GL function. Forwarding
///   functions of GL's signatures (over a loader's own types, as glbinding's) or a macro for each
///   name (reading through a pointer to the current context's table, as glad's MX global mode does)
///   serve as well. Each name must be callable with GL's arguments; the glIs* functions are also
///   passed as values, and glClipControl must be a function or a function pointer: the state guard
///   compares it with nullptr to learn whether the loader found it (a forwarding function is never
///   null, so on a GL 4.5 context its table must hold glClipControl, as every 4.5 driver gives it).
///
/// Every function is core OpenGL 4.5 or older (glClipControl is 4.5, asked for only on a 4.5 context;
/// KHR_debug's groups are 4.3); the back end asks for a 4.3 context.

#define HAIRSHADOW_GL_FUNCTION_COUNT 126

/// X(glName, PFNGLNAMEPROC) for each GL function the library calls, sorted by name.
#define HAIRSHADOW_GL_FUNCTIONS(X) \
    X(glActiveTexture, PFNGLACTIVETEXTUREPROC) \
    X(glAttachShader, PFNGLATTACHSHADERPROC) \
    X(glBeginQuery, PFNGLBEGINQUERYPROC) \
    X(glBindBuffer, PFNGLBINDBUFFERPROC) \
    X(glBindBufferBase, PFNGLBINDBUFFERBASEPROC) \
    X(glBindBufferRange, PFNGLBINDBUFFERRANGEPROC) \
    X(glBindFramebuffer, PFNGLBINDFRAMEBUFFERPROC) \
    X(glBindImageTexture, PFNGLBINDIMAGETEXTUREPROC) \
    X(glBindRenderbuffer, PFNGLBINDRENDERBUFFERPROC) \
    X(glBindSampler, PFNGLBINDSAMPLERPROC) \
    X(glBindTexture, PFNGLBINDTEXTUREPROC) \
    X(glBindVertexArray, PFNGLBINDVERTEXARRAYPROC) \
    X(glBlendEquation, PFNGLBLENDEQUATIONPROC) \
    X(glBlendEquationSeparate, PFNGLBLENDEQUATIONSEPARATEPROC) \
    X(glBlendEquationSeparatei, PFNGLBLENDEQUATIONSEPARATEIPROC) \
    X(glBlendEquationi, PFNGLBLENDEQUATIONIPROC) \
    X(glBlendFunc, PFNGLBLENDFUNCPROC) \
    X(glBlendFuncSeparatei, PFNGLBLENDFUNCSEPARATEIPROC) \
    X(glBlitFramebuffer, PFNGLBLITFRAMEBUFFERPROC) \
    X(glBufferData, PFNGLBUFFERDATAPROC) \
    X(glBufferSubData, PFNGLBUFFERSUBDATAPROC) \
    X(glCheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC) \
    X(glClear, PFNGLCLEARPROC) \
    X(glClearBufferData, PFNGLCLEARBUFFERDATAPROC) \
    X(glClearBufferfv, PFNGLCLEARBUFFERFVPROC) \
    X(glClearBufferuiv, PFNGLCLEARBUFFERUIVPROC) \
    X(glClientWaitSync, PFNGLCLIENTWAITSYNCPROC) \
    X(glClipControl, PFNGLCLIPCONTROLPROC) \
    X(glColorMask, PFNGLCOLORMASKPROC) \
    X(glColorMaski, PFNGLCOLORMASKIPROC) \
    X(glCompileShader, PFNGLCOMPILESHADERPROC) \
    X(glCopyBufferSubData, PFNGLCOPYBUFFERSUBDATAPROC) \
    X(glCreateProgram, PFNGLCREATEPROGRAMPROC) \
    X(glCreateShader, PFNGLCREATESHADERPROC) \
    X(glDeleteBuffers, PFNGLDELETEBUFFERSPROC) \
    X(glDeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC) \
    X(glDeleteProgram, PFNGLDELETEPROGRAMPROC) \
    X(glDeleteQueries, PFNGLDELETEQUERIESPROC) \
    X(glDeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC) \
    X(glDeleteShader, PFNGLDELETESHADERPROC) \
    X(glDeleteSync, PFNGLDELETESYNCPROC) \
    X(glDeleteTextures, PFNGLDELETETEXTURESPROC) \
    X(glDeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC) \
    X(glDepthFunc, PFNGLDEPTHFUNCPROC) \
    X(glDepthMask, PFNGLDEPTHMASKPROC) \
    X(glDisable, PFNGLDISABLEPROC) \
    X(glDisablei, PFNGLDISABLEIPROC) \
    X(glDispatchCompute, PFNGLDISPATCHCOMPUTEPROC) \
    X(glDrawArrays, PFNGLDRAWARRAYSPROC) \
    X(glDrawBuffers, PFNGLDRAWBUFFERSPROC) \
    X(glDrawElements, PFNGLDRAWELEMENTSPROC) \
    X(glEnable, PFNGLENABLEPROC) \
    X(glEnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC) \
    X(glEnablei, PFNGLENABLEIPROC) \
    X(glEndQuery, PFNGLENDQUERYPROC) \
    X(glFenceSync, PFNGLFENCESYNCPROC) \
    X(glFinish, PFNGLFINISHPROC) \
    X(glFramebufferParameteri, PFNGLFRAMEBUFFERPARAMETERIPROC) \
    X(glFramebufferRenderbuffer, PFNGLFRAMEBUFFERRENDERBUFFERPROC) \
    X(glFramebufferTexture, PFNGLFRAMEBUFFERTEXTUREPROC) \
    X(glFramebufferTextureLayer, PFNGLFRAMEBUFFERTEXTURELAYERPROC) \
    X(glGenBuffers, PFNGLGENBUFFERSPROC) \
    X(glGenFramebuffers, PFNGLGENFRAMEBUFFERSPROC) \
    X(glGenQueries, PFNGLGENQUERIESPROC) \
    X(glGenRenderbuffers, PFNGLGENRENDERBUFFERSPROC) \
    X(glGenTextures, PFNGLGENTEXTURESPROC) \
    X(glGenVertexArrays, PFNGLGENVERTEXARRAYSPROC) \
    X(glGetBooleani_v, PFNGLGETBOOLEANI_VPROC) \
    X(glGetBufferParameteri64v, PFNGLGETBUFFERPARAMETERI64VPROC) \
    X(glGetBufferSubData, PFNGLGETBUFFERSUBDATAPROC) \
    X(glGetError, PFNGLGETERRORPROC) \
    X(glGetFloati_v, PFNGLGETFLOATI_VPROC) \
    X(glGetFloatv, PFNGLGETFLOATVPROC) \
    X(glGetInteger64i_v, PFNGLGETINTEGER64I_VPROC) \
    X(glGetInteger64v, PFNGLGETINTEGER64VPROC) \
    X(glGetIntegeri_v, PFNGLGETINTEGERI_VPROC) \
    X(glGetIntegerv, PFNGLGETINTEGERVPROC) \
    X(glGetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC) \
    X(glGetProgramiv, PFNGLGETPROGRAMIVPROC) \
    X(glGetQueryObjectuiv, PFNGLGETQUERYOBJECTUIVPROC) \
    X(glGetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC) \
    X(glGetShaderiv, PFNGLGETSHADERIVPROC) \
    X(glGetString, PFNGLGETSTRINGPROC) \
    X(glGetTexImage, PFNGLGETTEXIMAGEPROC) \
    X(glGetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC) \
    X(glIsBuffer, PFNGLISBUFFERPROC) \
    X(glIsEnabled, PFNGLISENABLEDPROC) \
    X(glIsEnabledi, PFNGLISENABLEDIPROC) \
    X(glIsFramebuffer, PFNGLISFRAMEBUFFERPROC) \
    X(glIsProgram, PFNGLISPROGRAMPROC) \
    X(glIsSampler, PFNGLISSAMPLERPROC) \
    X(glIsTexture, PFNGLISTEXTUREPROC) \
    X(glIsVertexArray, PFNGLISVERTEXARRAYPROC) \
    X(glLineWidth, PFNGLLINEWIDTHPROC) \
    X(glLinkProgram, PFNGLLINKPROGRAMPROC) \
    X(glLogicOp, PFNGLLOGICOPPROC) \
    X(glMemoryBarrier, PFNGLMEMORYBARRIERPROC) \
    X(glPixelStorei, PFNGLPIXELSTOREIPROC) \
    X(glPolygonMode, PFNGLPOLYGONMODEPROC) \
    X(glPopDebugGroup, PFNGLPOPDEBUGGROUPPROC) \
    X(glProgramUniform1f, PFNGLPROGRAMUNIFORM1FPROC) \
    X(glProgramUniform1i, PFNGLPROGRAMUNIFORM1IPROC) \
    X(glProgramUniformMatrix4fv, PFNGLPROGRAMUNIFORMMATRIX4FVPROC) \
    X(glPushDebugGroup, PFNGLPUSHDEBUGGROUPPROC) \
    X(glReadBuffer, PFNGLREADBUFFERPROC) \
    X(glReadPixels, PFNGLREADPIXELSPROC) \
    X(glRenderbufferStorage, PFNGLRENDERBUFFERSTORAGEPROC) \
    X(glRenderbufferStorageMultisample, PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC) \
    X(glShaderSource, PFNGLSHADERSOURCEPROC) \
    X(glTexParameteri, PFNGLTEXPARAMETERIPROC) \
    X(glTexStorage2D, PFNGLTEXSTORAGE2DPROC) \
    X(glTexStorage3D, PFNGLTEXSTORAGE3DPROC) \
    X(glUniform1f, PFNGLUNIFORM1FPROC) \
    X(glUniform1i, PFNGLUNIFORM1IPROC) \
    X(glUniform1ui, PFNGLUNIFORM1UIPROC) \
    X(glUniform2f, PFNGLUNIFORM2FPROC) \
    X(glUniform2i, PFNGLUNIFORM2IPROC) \
    X(glUniform2ui, PFNGLUNIFORM2UIPROC) \
    X(glUniform3fv, PFNGLUNIFORM3FVPROC) \
    X(glUniform4f, PFNGLUNIFORM4FPROC) \
    X(glUniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC) \
    X(glUseProgram, PFNGLUSEPROGRAMPROC) \
    X(glVertexAttribDivisor, PFNGLVERTEXATTRIBDIVISORPROC) \
    X(glVertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC) \
    X(glViewport, PFNGLVIEWPORTPROC) \
    X(glViewportIndexedfv, PFNGLVIEWPORTINDEXEDFVPROC)
