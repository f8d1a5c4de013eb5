// libOSMesa, opened with dlopen on the first PNG figure instead of linked: it brings LLVM (llvmpipe), whose
// relocations alone cost every `ipd` run tens of milliseconds at start-up. The OSMesa and OpenGL functions
// the off-screen renderer and Dear ImGui's OpenGL 2 backend call are defined here, each forwarding to the
// library's own (looked up once). Only `ipd` does this; ipd-studio links libGL and never OSMesa.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace {

constexpr const char* kOsMesaLibrary = "libOSMesa.so.8";

struct Library {
  void* handle = nullptr;  // never closed
  std::string error;       // why it could not be opened
};

const Library& library() {
  static const Library l = [] {
    Library out;
    out.handle = dlopen(kOsMesaLibrary, RTLD_NOW | RTLD_LOCAL);
    if (!out.handle) out.error = dlerror();
    return out;
  }();
  return l;
}

void* osmesa_symbol(const char* name) {
  const Library& l = library();
  if (!l.handle)
    throw std::runtime_error(std::string("PNG figures need ") + kOsMesaLibrary +
                             " (Debian package libosmesa6), which cannot be opened: " + l.error);
  void* f = dlsym(l.handle, name);
  if (!f) throw std::runtime_error(std::string(kOsMesaLibrary) + " has no " + name);
  return f;
}

}  // namespace

// Each definition must have the header's exact type (a C function can't be overloaded: a wrong one fails to
// compile). The executable does not export them (no library it links calls them), so libOSMesa's own calls
// never land here.
#define IPD_FORWARD(ret, name, params, args)                                                        \
  extern "C" ret GLAPIENTRY name params {                                                           \
    static const auto forward_to = reinterpret_cast<ret(GLAPIENTRY*) params>(osmesa_symbol(#name)); \
    return forward_to args;                                                                         \
  }

IPD_FORWARD(OSMesaContext, OSMesaCreateContextExt,
            (GLenum format, GLint depth, GLint stencil, GLint accum, OSMesaContext share),
            (format, depth, stencil, accum, share))
IPD_FORWARD(GLboolean, OSMesaMakeCurrent, (OSMesaContext c, void* buffer, GLenum type, GLsizei w, GLsizei h),
            (c, buffer, type, w, h))
IPD_FORWARD(void, OSMesaPixelStore, (GLint pname, GLint value), (pname, value))
IPD_FORWARD(void, OSMesaDestroyContext, (OSMesaContext c), (c))

IPD_FORWARD(void, glBindTexture, (GLenum target, GLuint texture), (target, texture))
IPD_FORWARD(void, glBlendFunc, (GLenum s, GLenum d), (s, d))
IPD_FORWARD(void, glClear, (GLbitfield mask), (mask))
IPD_FORWARD(void, glClearColor, (GLclampf r, GLclampf g, GLclampf b, GLclampf a), (r, g, b, a))
IPD_FORWARD(void, glColorPointer, (GLint size, GLenum type, GLsizei stride, const GLvoid* p), (size, type, stride, p))
IPD_FORWARD(void, glDeleteTextures, (GLsizei n, const GLuint* textures), (n, textures))
IPD_FORWARD(void, glDisable, (GLenum cap), (cap))
IPD_FORWARD(void, glDisableClientState, (GLenum cap), (cap))
IPD_FORWARD(void, glDrawElements, (GLenum mode, GLsizei count, GLenum type, const GLvoid* indices),
            (mode, count, type, indices))
IPD_FORWARD(void, glEnable, (GLenum cap), (cap))
IPD_FORWARD(void, glEnableClientState, (GLenum cap), (cap))
IPD_FORWARD(void, glFinish, (void), ())
IPD_FORWARD(void, glGenTextures, (GLsizei n, GLuint* textures), (n, textures))
IPD_FORWARD(void, glGetIntegerv, (GLenum pname, GLint* params), (pname, params))
IPD_FORWARD(void, glGetTexEnviv, (GLenum target, GLenum pname, GLint* params), (target, pname, params))
IPD_FORWARD(void, glLoadIdentity, (void), ())
IPD_FORWARD(void, glMatrixMode, (GLenum mode), (mode))
IPD_FORWARD(void, glOrtho, (GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f), (l, r, b, t, n, f))
IPD_FORWARD(void, glPixelStorei, (GLenum pname, GLint param), (pname, param))
IPD_FORWARD(void, glPolygonMode, (GLenum face, GLenum mode), (face, mode))
IPD_FORWARD(void, glPopAttrib, (void), ())
IPD_FORWARD(void, glPopMatrix, (void), ())
IPD_FORWARD(void, glPushAttrib, (GLbitfield mask), (mask))
IPD_FORWARD(void, glPushMatrix, (void), ())
IPD_FORWARD(void, glScissor, (GLint x, GLint y, GLsizei w, GLsizei h), (x, y, w, h))
IPD_FORWARD(void, glShadeModel, (GLenum mode), (mode))
IPD_FORWARD(void, glTexCoordPointer, (GLint size, GLenum type, GLsizei stride, const GLvoid* p),
            (size, type, stride, p))
IPD_FORWARD(void, glTexEnvi, (GLenum target, GLenum pname, GLint param), (target, pname, param))
IPD_FORWARD(void, glTexImage2D,
            (GLenum target, GLint level, GLint internal, GLsizei w, GLsizei h, GLint border, GLenum format, GLenum type,
             const GLvoid* pixels),
            (target, level, internal, w, h, border, format, type, pixels))
IPD_FORWARD(void, glTexParameteri, (GLenum target, GLenum pname, GLint param), (target, pname, param))
IPD_FORWARD(void, glVertexPointer, (GLint size, GLenum type, GLsizei stride, const GLvoid* p), (size, type, stride, p))
IPD_FORWARD(void, glViewport, (GLint x, GLint y, GLsizei w, GLsizei h), (x, y, w, h))
