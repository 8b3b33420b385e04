#include "realtime/gl_utils.h"

#include <vector>

namespace relight::gl {

namespace {

// The log of a shader or program whose `status` (compile or link) is not
// set, "" where it is: get_iv and get_log are the glGetShader* or
// glGetProgram* pair.
template <class GetIv, class GetLog>
std::string failure_log(GLuint object, GLenum status, GetIv get_iv, GetLog get_log) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return {};
  char log[4096];
  get_log(object, GLsizei(sizeof log), nullptr, log);
  return log[0] ? log : "(no log)";
}

GLuint compile_shader(GLenum type, const char* source, std::string& why) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  const std::string log = failure_log(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog);
  if (log.empty()) return shader;
  why = "shader does not compile: " + log;
  glDeleteShader(shader);
  return 0;
}

}  // namespace

GLuint link_program(std::initializer_list<Stage> stages, std::string& why) {
  std::vector<GLuint> shaders;
  const auto drop_shaders = [&] {
    for (GLuint shader : shaders) glDeleteShader(shader);
  };
  for (const Stage& stage : stages) {
    const GLuint shader = compile_shader(stage.type, stage.source, why);
    if (!shader) {
      drop_shaders();
      return 0;
    }
    shaders.push_back(shader);
  }
  const GLuint program = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  drop_shaders();
  const std::string log = failure_log(program, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog);
  if (log.empty()) return program;
  why = "shader program does not link: " + log;
  glDeleteProgram(program);
  return 0;
}

GLuint float_texture(int width, int height, GLenum internal_format, GLenum format, const float* data) {
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), width, height, 0, format, GL_FLOAT, data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return tex;
}

void set_shadow_sampling(GLenum target) {
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

}  // namespace relight::gl
