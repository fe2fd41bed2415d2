#pragma once
// One place that includes OpenGL: its types and constants from the core-profile header, and the
// table of the functions coinroll calls, loaded from the back end that made the context.
//
// Why a table and not plain glFoo symbols: libOSMesa exports the GL API itself, and so does
// libOpenGL (glvnd, which EGL contexts go through); with both linked, every plain glFoo would bind
// to whichever library the dynamic linker finds first, and calls meant for an EGL context would
// land in OSMesa's dispatch (or the reverse). Each back end resolves the table through its own
// GetProcAddress instead, and this header declares no GL prototypes, so a plain glFoo call does not
// compile.

#include <GL/glcorearb.h>

namespace coinroll::render {

// The GL functions coinroll calls (the renderer, and the probe in bench/render_bench.cpp), exactly
// those: a new call needs a line here. X(type, name) declares member `name` of type `type`,
// resolved as "gl" #name. Members keep OpenGL's names without the gl prefix, so
// `gl.BindBuffer(...)` reads as the glBindBuffer the GL reference documents.
#define COINROLL_GL_FUNCTIONS(X)                                             \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                           \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                         \
  X(PFNGLCLEARSTENCILPROC, ClearStencil)                                     \
  X(PFNGLCOLORMASKPROC, ColorMask)                                           \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                     \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                                 \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLSTENCILFUNCPROC, StencilFunc)                                       \
  X(PFNGLSTENCILMASKPROC, StencilMask)                                       \
  X(PFNGLSTENCILOPPROC, StencilOp)                                           \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM2FVPROC, Uniform2fv)                                         \
  X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                         \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                           \
  X(PFNGLUNIFORM4FVPROC, Uniform4fv)                                         \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                             \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLVIEWPORTPROC, Viewport)

// Entry points of one context's back end. Calls go to the context current on the calling thread,
// as with plain GL, so make the owning context current first (GlContext::makeCurrent).
struct GlFunctions {
#define COINROLL_GL_MEMBER(type, name) type name = nullptr;
  COINROLL_GL_FUNCTIONS(COINROLL_GL_MEMBER)
#undef COINROLL_GL_MEMBER
};

// A back end's lookup of a GL function by name ("glBindBuffer"): OSMesaGetProcAddress,
// eglGetProcAddress. Returns null for a name it does not know.
using GlProcedure = void (*)();
using GlProcedureLookup = GlProcedure (*)(const char* name);

// Resolves every function of the table through `lookup`. Throws std::runtime_error naming the
// first one missing and `backendName` (for the message).
GlFunctions loadGlFunctions(GlProcedureLookup lookup, const char* backendName);

}  // namespace coinroll::render
