// The studio's textures in OpenGL: a mipmap chain per picture, built on the decoder thread (picture_loader.h).
#include "app/studio/studio_gl_textures.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>

namespace ipd::studio {

namespace {

class GlTextures : public TextureBackend {
 public:
  unsigned create(const std::vector<cv::Mat>& levels) override {
    unsigned id = 0;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    // Mipmaps: pictures are mostly shown smaller than they are; sampling a reduced level is smoother and
    // much cheaper for a software rasteriser.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels.size() > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, static_cast<int>(levels.size()) - 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    for (size_t level = 0; level < levels.size(); ++level) {
      const cv::Mat& m = levels[level];
      glTexImage2D(GL_TEXTURE_2D, static_cast<int>(level), GL_RGBA, m.cols, m.rows, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   m.data);
    }
    return id;
  }
  void destroy(unsigned id) override { glDeleteTextures(1, &id); }
};

}  // namespace

std::unique_ptr<TextureBackend> gl_textures() { return std::make_unique<GlTextures>(); }

}  // namespace ipd::studio
