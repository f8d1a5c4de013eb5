// OpenGL textures for the studio's texture cache (ipd-studio only: the tests use a fake backend).
#pragma once

#include <memory>

#include "app/studio/studio_textures.h"

namespace ipd::studio {

// A backend for the current GL context; call from the GL thread.
std::unique_ptr<TextureBackend> gl_textures();

}  // namespace ipd::studio
