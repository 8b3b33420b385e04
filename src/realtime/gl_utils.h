// Small OpenGL utilities of the backend (a current context required):
// shader programs, float and shadow-map textures.
#pragma once

#include <epoxy/gl.h>

#include <string>

namespace relight::gl {

// Compiles and links a program: 0, with the compiler's or linker's log in
// `why`, where that fails.
GLuint link_program(const char* vertex, const char* fragment, std::string& why);

// A 2D float texture, nearest-neighbour sampled; data may be null.
GLuint float_texture(int width, int height, GLenum internal_format, GLenum format, const float* data);

// A depth texture (2D or cube map) sampled by shadow comparison, bilinear.
void set_shadow_sampling(GLenum target);

}  // namespace relight::gl
