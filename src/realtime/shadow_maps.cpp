#include "realtime/shadow_maps.h"

#include <epoxy/gl.h>
#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/sampling.h"
#include "realtime/egl_context.h"
#include "realtime/gl_utils.h"
#include "realtime/glsl_sources.h"
#include "realtime/light_views.h"

namespace relight {

namespace {

// The shading shader's source for one variant (see glsl/shade.glsl), as a
// compute or a fragment shader.
std::string shade_source(bool compute, int light_type, int map_kind, int pcf_radius, bool extended) {
  return std::string(compute ? "#version 430 core" : "#version 330 core") + "\n#define LIGHT_TYPE " +
         std::to_string(light_type) + "\n#define MAP_KIND " + std::to_string(map_kind) + "\n#define PCF_RADIUS " +
         std::to_string(pcf_radius) + "\n#define EXTENDED " + (extended ? "1" : "0") + "\n" + glsl::shade_glsl +
         (compute ? glsl::shade_comp : glsl::shade_frag);
}

}  // namespace

struct GlRelighter::State {
  std::unique_ptr<HeadlessContext> context;
  ShadowMapOptions options;
  std::optional<LightViews> views;
  int width = 0, height = 0;
  bool compute = false;  // shading by compute shader (else by fragment shader)
  GLuint mesh_vao = 0, mesh_vbo = 0, mesh_ebo = 0, screen_vao = 0;
  GLsizei index_count = 0;
  GLuint position_tex = 0, normal_tex = 0, gnormal_tex = 0;
  GLuint flat_depth = 0, sun_depth = 0, cube_depth = 0;
  // A framebuffer for each shadow map (each cube face): binding one is
  // cheaper than attaching another map to one framebuffer, which a driver
  // validates anew each time.
  GLuint flat_fbo = 0, sun_fbo = 0, cube_fbos[6] = {};
  GLuint light_tex = 0, light_fbo = 0, readback_buffer = 0;
  GLuint depth_program = 0;
  std::map<std::tuple<int, int, int, bool>, GLuint> shade_programs;

  ~State() {
    if (!context) return;
    HeadlessContext::Current current(*context);
    const GLuint textures[] = {position_tex, normal_tex, gnormal_tex, flat_depth, sun_depth, cube_depth, light_tex};
    glDeleteTextures(7, textures);
    const GLuint framebuffers[] = {flat_fbo, sun_fbo, light_fbo};
    glDeleteFramebuffers(3, framebuffers);
    glDeleteFramebuffers(6, cube_fbos);
    const GLuint buffers[] = {mesh_vbo, mesh_ebo, readback_buffer};
    glDeleteBuffers(3, buffers);
    const GLuint arrays[] = {mesh_vao, screen_vao};
    glDeleteVertexArrays(2, arrays);
    glDeleteProgram(depth_program);
    for (const auto& [key, program] : shade_programs) glDeleteProgram(program);
  }

  GLuint flat_map_of(const LightSamplePoint& s) const {
    return s.map == LightSamplePoint::Map::orthographic ? sun_depth : flat_depth;
  }
  GLuint flat_fbo_of(const LightSamplePoint& s) const {
    return s.map == LightSamplePoint::Map::orthographic ? sun_fbo : flat_fbo;
  }

  void render_shadow_map(const LightSamplePoint& sample);
  GLuint shade_program(int light_type, int map_kind, int pcf_radius, bool extended);
  void shade(const Light& light, const Vec3& emission, const LightSamplePoint& sample, bool add);
  void add_light(const Light& light, const Vec3& emission, bool first);
  void read(GLuint fbo, Image& out);
};

// ---- rendering ----

void GlRelighter::State::render_shadow_map(const LightSamplePoint& s) {
  glUseProgram(depth_program);
  const GLint vp = glGetUniformLocation(depth_program, "view_projection");
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glBindVertexArray(mesh_vao);
  if (s.map == LightSamplePoint::Map::cube) {
    glViewport(0, 0, s.side, s.side);
    const Mat4 projection = perspective(kPi / 2, s.near, s.far);
    for (int face = 0; face < 6; ++face) {
      glBindFramebuffer(GL_FRAMEBUFFER, cube_fbos[face]);
      glClear(GL_DEPTH_BUFFER_BIT);
      const Mat4 m = projection * cube_face_view(s.eye, face);
      glUniformMatrix4fv(vp, 1, GL_FALSE, m.data());
      glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
    }
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, flat_fbo_of(s));
    glViewport(0, 0, s.side, s.side);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUniformMatrix4fv(vp, 1, GL_FALSE, s.view_projection.data());
    glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
}

// The shading program for a light type, map kind and filter width, compiled
// on first use.
GLuint GlRelighter::State::shade_program(int light_type, int map_kind, int pcf_radius, bool extended) {
  GLuint& program = shade_programs[{light_type, map_kind, pcf_radius, extended}];
  if (!program) {
    std::string why;
    const std::string source = shade_source(compute, light_type, map_kind, pcf_radius, extended);
    program =
        compute ? gl::link_program({{GL_COMPUTE_SHADER, source.c_str()}}, why)
                : gl::link_program({{GL_VERTEX_SHADER, glsl::screen_vert}, {GL_FRAGMENT_SHADER, source.c_str()}}, why);
    if (!program) throw std::runtime_error("OpenGL backend: " + why);
  }
  return program;
}

// add: blend onto what the framebuffer holds (else overwrite it).
void GlRelighter::State::shade(const Light& light, const Vec3& emission, const LightSamplePoint& s, bool add) {
  const int type = light.type == LightType::point  ? 0
                   : light.type == LightType::spot ? 1
                   : light.type == LightType::area ? 2
                                                   : 3;
  // Hard shadows keep the hardware's bilinear 2x2 comparison only: wider
  // filtering would blur edges that shadow rays draw sharp.
  const int pcf = LightSampler(light).needs_random() ? std::clamp(options.pcf_radius, 0, 4) : 0;
  const GLuint p = shade_program(type, int(s.map), pcf, light.radius > 0.0f);
  glUseProgram(p);
  const auto loc = [&](const char* name) { return glGetUniformLocation(p, name); };
  glUniform1i(loc("surface_position"), 0);
  glUniform1i(loc("surface_normal"), 1);
  glUniform1i(loc("surface_gnormal"), 2);
  glUniform1i(loc("cube_map"), 3);
  glUniform1i(loc("flat_map"), 4);
  glUniform3fv(loc("emission"), 1, emission.data());
  glUniform3fv(loc("light_position"), 1, light.position.data());
  const Vec3 axis = light.type == LightType::directional ? s.sun_direction : Vec3(light.direction.normalized());
  glUniform3fv(loc("light_axis"), 1, axis.data());
  glUniform1f(loc("cos_outer"), std::cos(radians(light.spot_angle_deg) * 0.5f));
  glUniform1f(loc("blend"), light.blend);
  glUniform2fv(loc("disc_offset"), 1, s.disc_offset.data());
  glUniform3fv(loc("area_point"), 1, s.area_point.data());
  glUniform3fv(loc("map_eye"), 1, s.eye.data());
  glUniformMatrix4fv(loc("map_view_projection"), 1, GL_FALSE, s.view_projection.data());
  glUniform3fv(loc("map_forward"), 1, s.forward.data());
  glUniform1f(loc("map_near"), s.near);
  glUniform1f(loc("map_far"), s.far);
  glUniform1f(loc("texel_per_depth"), s.texel_per_depth);
  glUniform1f(loc("texel_world"), s.texel_world);
  glUniform1f(loc("map_size"), float(s.side));
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, flat_map_of(s));
  glUniform1f(loc("normal_offset"), options.normal_offset);
  glUniform1f(loc("depth_offset"), options.depth_offset);
  glUniform2f(loc("distance_range"), s.distance_range.x(), std::min(s.distance_range.y(), 3.0e38f));
  if (compute) {
    glUniform1i(loc("accumulate"), add);
    glBindImageTexture(0, light_tex, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glDispatchCompute(GLuint(width + 7) / 8, GLuint(height + 7) / 8, 1);
    // The next sample adds to what this one wrote; the readback reads it.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
    return;
  }

  glBindFramebuffer(GL_FRAMEBUFFER, light_fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  if (add) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);  // the samples and lights add up
  }
  glBindVertexArray(screen_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDisable(GL_BLEND);
}

// Adds the light's direct light to the light framebuffer; the first light
// drawn overwrites it (first: no clearing or blending needed).
void GlRelighter::State::add_light(const Light& light, const Vec3& emission, bool first) {
  for (const LightSamplePoint& s : views->samples_of(light)) {
    render_shadow_map(s);
    shade(light, emission * s.weight, s, !first);
    first = false;
  }
}

// Reads the light back into `out` through a pixel buffer (the driver copies
// into it directly), then copies it out on every core: at 1920x1080 this is
// 25 MB a frame, the larger part of a frame on a fast GPU.
void GlRelighter::State::read(GLuint fbo, Image& out) {
  static_assert(sizeof(Vec3) == 3 * sizeof(float), "an image's pixels are packed RGB floats");
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, readback_buffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  // Framebuffer row y holds view row y (the textures were uploaded top row first).
  glReadPixels(0, 0, width, height, GL_RGB, GL_FLOAT, nullptr);
  if (out.width != width || out.height != height) out = Image(width, height);
  const size_t row = size_t(width) * sizeof(Vec3);
  const auto* pixels =
      static_cast<const char*>(glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(row * height), GL_MAP_READ_BIT));
  if (pixels) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 16), [&](const tbb::blocked_range<int>& rows) {
      std::memcpy(reinterpret_cast<char*>(out.pixels.data()) + row * size_t(rows.begin()),
                  pixels + row * size_t(rows.begin()), row * size_t(rows.size()));
    });
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

// ---- setup ----

std::unique_ptr<GlRelighter> GlRelighter::open(const TriangleMesh& mesh, const PixelSurfaces& surfaces,
                                               const ShadowMapOptions& options, std::string& why) {
  auto state = std::make_unique<State>();
  state->context = HeadlessContext::open(why);
  if (!state->context) return nullptr;
  HeadlessContext::Current current(*state->context);
  state->options = options;
  state->options.size = std::max(16, options.size);
  state->options.sun_size = std::max(16, options.sun_size);
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  state->options.size = std::min(state->options.size, int(max_size));
  state->options.sun_size = std::min(state->options.sun_size, int(max_size));
  const int w = surfaces.width, h = surfaces.height;
  state->width = w;
  state->height = h;
  state->views.emplace(state->options, mesh.bounds(), surfaces);
  using Shading = ShadowMapOptions::Shading;
  const bool has_compute = epoxy_gl_version() >= 43;
  state->compute = has_compute && (options.shading == Shading::compute ||
                                   (options.shading == Shading::automatic && !state->context->software()));

  state->depth_program =
      gl::link_program({{GL_VERTEX_SHADER, glsl::depth_vert}, {GL_FRAGMENT_SHADER, glsl::depth_frag}}, why);
  if (!state->depth_program) return nullptr;
  try {
    state->shade_program(0, 0, 0, false);  // one variant now: a driver that cannot compile it is no backend
  } catch (const std::exception& e) {
    why = e.what();
    return nullptr;
  }

  // The mesh, for the shadow maps.
  glGenVertexArrays(1, &state->mesh_vao);
  glBindVertexArray(state->mesh_vao);
  glGenBuffers(1, &state->mesh_vbo);
  glBindBuffer(GL_ARRAY_BUFFER, state->mesh_vbo);
  std::vector<float> positions;
  positions.reserve(mesh.positions.size() * 3);
  for (const Vec3& p : mesh.positions) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(float)), positions.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glEnableVertexAttribArray(0);
  glGenBuffers(1, &state->mesh_ebo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, state->mesh_ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.triangles.size() * sizeof(mesh.triangles[0])),
               mesh.triangles.data(), GL_STATIC_DRAW);
  state->index_count = GLsizei(mesh.triangles.size() * 3);
  glGenVertexArrays(1, &state->screen_vao);

  // The view: what each pixel sees, as textures (top row first).
  std::vector<float> position(size_t(w) * h * 4, 0.0f), normal(size_t(w) * h * 4), gnormal(size_t(w) * h * 4);
  for (size_t i = 0; i < surfaces.surface.size(); ++i) {
    const SurfacePoint& s = surfaces.surface[i];
    if (surfaces.hit[i]) {
      for (int c = 0; c < 3; ++c) position[4 * i + c] = s.position[c];
      position[4 * i + 3] = 1.0f;
    }
    for (int c = 0; c < 3; ++c) {
      normal[4 * i + c] = s.normal[c];
      gnormal[4 * i + c] = s.geometric_normal[c];
    }
    normal[4 * i + 3] = s.lift;
    gnormal[4 * i + 3] = s.distance;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  state->position_tex = gl::float_texture(w, h, GL_RGBA32F, GL_RGBA, position.data());
  state->normal_tex = gl::float_texture(w, h, GL_RGBA32F, GL_RGBA, normal.data());
  state->gnormal_tex = gl::float_texture(w, h, GL_RGBA32F, GL_RGBA, gnormal.data());

  // Shadow maps: a perspective one, the sun's, a cube, reused by every light sample.
  for (auto [tex, size] :
       {std::pair{&state->flat_depth, state->options.size}, std::pair{&state->sun_depth, state->options.sun_size}}) {
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    gl::set_shadow_sampling(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  const int cube = state->views->cube_size();
  glGenTextures(1, &state->cube_depth);
  glBindTexture(GL_TEXTURE_CUBE_MAP, state->cube_depth);
  for (int face = 0; face < 6; ++face)
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_DEPTH_COMPONENT32F, cube, cube, 0, GL_DEPTH_COMPONENT,
                 GL_FLOAT, nullptr);
  gl::set_shadow_sampling(GL_TEXTURE_CUBE_MAP);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  const auto depth_framebuffer = [](GLenum target, GLuint texture) {
    GLuint fbo = 0;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, target, texture, 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    return fbo;
  };
  state->flat_fbo = depth_framebuffer(GL_TEXTURE_2D, state->flat_depth);
  state->sun_fbo = depth_framebuffer(GL_TEXTURE_2D, state->sun_depth);
  for (int face = 0; face < 6; ++face)
    state->cube_fbos[face] = depth_framebuffer(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, state->cube_depth);

  // The light accumulates in a float framebuffer.
  state->light_tex = gl::float_texture(w, h, GL_RGBA32F, GL_RGBA, nullptr);
  glGenFramebuffers(1, &state->light_fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, state->light_fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, state->light_tex, 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    why = "a float framebuffer is not supported";
    return nullptr;
  }
  glGenBuffers(1, &state->readback_buffer);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, state->readback_buffer);
  glBufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(size_t(w) * h * sizeof(Vec3)), nullptr, GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glDisable(GL_CULL_FACE);  // both sides of every surface cast shadows
  if (glGetError() != GL_NO_ERROR) {
    why = "OpenGL error while setting up";
    return nullptr;
  }
  spdlog::info("OpenGL backend: {} ({}), shading by {} shader", state->context->renderer(), state->context->version(),
               state->compute ? "compute" : "fragment");
  return std::unique_ptr<GlRelighter>(new GlRelighter(std::move(state)));
}

GlRelighter::GlRelighter(std::unique_ptr<State> state) : state_(std::move(state)) {}
GlRelighter::~GlRelighter() = default;

const std::string& GlRelighter::renderer() const { return state_->context->renderer(); }
bool GlRelighter::shades_by_compute() const { return state_->compute; }

namespace {

// Binds the view's textures and the shadow maps to their units.
void bind_textures(GLuint position, GLuint normal, GLuint gnormal, GLuint cube, GLuint flat) {
  const std::pair<GLenum, GLuint> units[] = {{GL_TEXTURE_2D, position},
                                             {GL_TEXTURE_2D, normal},
                                             {GL_TEXTURE_2D, gnormal},
                                             {GL_TEXTURE_CUBE_MAP, cube},
                                             {GL_TEXTURE_2D, flat}};
  for (int i = 0; i < 5; ++i) {
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(units[i].first, units[i].second);
  }
}

}  // namespace

void GlRelighter::render(const Light& light, Image& out) {
  State& s = *state_;
  HeadlessContext::Current current(*s.context);
  bind_textures(s.position_tex, s.normal_tex, s.gnormal_tex, s.cube_depth, s.flat_depth);
  s.add_light(light, light.emission(), true);
  s.read(s.light_fbo, out);
}

}  // namespace relight
