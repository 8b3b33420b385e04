// Small OpenGL utilities of the backend (a current context required):
// shader programs, float and shadow-map textures.
#pragma once

#include <epoxy/gl.h>

#include <initializer_list>
#include <string>

namespace relight::gl {

// One shader of a program: its type (GL_VERTEX_SHADER...) and source.
struct Stage {
  GLenum type;
  const char* source;
};

// Compiles and links a program: 0, with the compiler's or linker's log in
// `why`, where that fails.
GLuint link_program(std::initializer_list<Stage> stages, std::string& why);

// A 2D float texture, nearest-neighbour sampled; data may be null.
GLuint float_texture(int width, int height, GLenum internal_format, GLenum format, const float* data);

// A depth texture (2D or cube map) sampled by shadow comparison, bilinear.
void set_shadow_sampling(GLenum target);

}  // namespace relight::gl
