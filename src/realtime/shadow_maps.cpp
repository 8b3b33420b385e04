#include "realtime/shadow_maps.h"

#include <epoxy/gl.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

#include "core/sampling.h"
#include "realtime/egl_context.h"

namespace relight {

namespace {

using Mat4 = Eigen::Matrix4f;

// ---- shaders ----

// Depth of the scene as seen from a light: the shadow map.
constexpr const char* kDepthVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * vec4(position, 1.0); }
)";
constexpr const char* kDepthFragment = R"(#version 330 core
void main() {}
)";

// A triangle covering the framebuffer: one fragment per view pixel.
constexpr const char* kScreenVertex = R"(#version 330 core
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// One light sample's direct light at each pixel's surface, times its shadow
// map's visibility: the radiometry of LightSampler (src/scene/light.cpp)
// for one fixed point on the light (or direction of the sun). Compiled for
// each light type, map kind, filter width and extent (LIGHT_TYPE, MAP_KIND,
// PCF_RADIUS, EXTENDED): a software rasteriser runs all the code it cannot
// rule out.
constexpr const char* kShadeFragment = R"(
const int light_type = LIGHT_TYPE;    // 0 point, 1 spot, 2 area, 3 sun
const int pcf_radius = PCF_RADIUS;
uniform sampler2D surface_position;   // xyz; w = 1 where the pixel sees a surface
uniform sampler2D surface_normal;     // shading normal
uniform sampler2D surface_gnormal;    // the triangle's normal; w: distance from the camera
uniform samplerCubeShadow cube_map;   // MAP_KIND 0
uniform sampler2DShadow flat_map;     // MAP_KIND 1 (perspective), 2 (orthographic)

uniform vec3 emission;                // times the sample's weight
uniform vec3 light_position;
uniform vec3 light_axis;              // spot: where it points; area: the side that emits; sun: towards it
uniform float cos_outer;              // spot: cos(spot_angle / 2)
uniform float blend;
uniform vec2 disc_offset;             // EXTENDED point/spot: the sample on the disc (m), in the disc's own frame
uniform vec3 area_point;              // area: the sample on the rectangle

uniform vec3 map_eye;                 // cube/perspective: where the map looks from
uniform mat4 map_view_projection;     // perspective/orthographic
uniform vec3 map_forward;             // perspective: the view axis
uniform float map_near, map_far;
uniform float texel_per_depth;        // cube/perspective: world size of a texel per metre of depth
uniform float texel_world;            // orthographic: world size of a texel
uniform float map_size;
uniform float normal_offset, depth_offset;
uniform vec2 distance_range;          // the pixels this map serves (a cascade of the sun's), by camera distance

out vec4 color;
const float PI = 3.14159265358979;
void orthonormal_basis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}
float spot_cone(float c) {
  float t = clamp((c - cos_outer) / max((1.0 - cos_outer) * blend, 1e-9), 0.0, 1.0);
  float s = blend > 0.0 ? t * t * (3.0 - 2.0 * t) : 1.0;
  return c > cos_outer ? c * s : 0.0;
}
// Unoccluded irradiance of the sample at p; `dir` gets the direction to it.
// Without branches where a select does: a software rasteriser runs both
// sides of a branch its lanes disagree on.
vec3 irradiance(vec3 p, vec3 n, out vec3 dir) {
#if LIGHT_TYPE == 3
  dir = light_axis;
  return emission * max(0.0, dot(n, dir));
#elif LIGHT_TYPE == 2
  vec3 to_light = area_point - p;
  float d2 = dot(to_light, to_light);
  dir = to_light * inversesqrt(d2);
  float cos_s = dot(n, dir), cos_l = -dot(light_axis, dir);
  // radiance power/(4 area) x cos_s cos_l area / d^2
  return (cos_s > 0.0 && cos_l > 0.0) ? emission * (cos_s * cos_l / (4.0 * d2)) : vec3(0.0);
#else
  vec3 to_center = light_position - p;
  vec3 axis = normalize(to_center);  // the disc faces p
  float cone = light_type == 1 ? spot_cone(dot(-axis, light_axis)) : 1.0;
#if EXTENDED
  vec3 t, b;
  orthonormal_basis(axis, t, b);
  vec3 to_light = to_center + disc_offset.x * t + disc_offset.y * b;
#else
  vec3 to_light = to_center;
#endif
  float d2 = dot(to_light, to_light);
  dir = to_light * inversesqrt(d2);
  float cos_s = dot(n, dir);
#if EXTENDED
  float cos_l = max(0.0, dot(axis, dir));
#else
  float cos_l = 1.0;
#endif
  return cos_s > 0.0 ? emission * (cone * cos_s * cos_l / (4.0 * PI * d2)) : vec3(0.0);
#endif
}
// Perspective depth-buffer value of a point `z` metres along the view axis.
float perspective_depth(float z) {
  float ndc = (map_far + map_near) / (map_far - map_near) - 2.0 * map_far * map_near / ((map_far - map_near) * z);
  return 0.5 * ndc + 0.5;
}
// The fraction of the sample's shadow map that sees p: percentage-closer
// filtering around p, which is first moved off its surface (normal offset)
// and towards the light (depth offset), both in texels. Outside a flat map
// nothing blocks.
float visibility(vec3 p, vec3 ng) {
  float lit = 0.0;
#if MAP_KIND == 0
  vec3 v = p - map_eye;
  float texel = texel_per_depth * max(abs(v.x), max(abs(v.y), abs(v.z)));
  v += ng * (normal_offset * texel);
  float m = max(abs(v.x), max(abs(v.y), abs(v.z)));
  float ref = perspective_depth(m - depth_offset * texel);
#if PCF_RADIUS == 0
  return texture(cube_map, vec4(v, ref));
#else
  vec3 t, b;
  orthonormal_basis(normalize(v), t, b);
  for (int i = -pcf_radius; i <= pcf_radius; ++i)
    for (int j = -pcf_radius; j <= pcf_radius; ++j)
      lit += texture(cube_map, vec4(v + (float(i) * t + float(j) * b) * texel, ref));
  return lit / float((2 * pcf_radius + 1) * (2 * pcf_radius + 1));
#endif
#else
#if MAP_KIND == 1
  float texel = texel_per_depth * max(dot(p - map_eye, map_forward), 0.0);
#else
  float texel = texel_world;
#endif
  vec3 q = p + ng * (normal_offset * texel);
  vec4 clip = map_view_projection * vec4(q, 1.0);
  vec3 ndc = clip.xyz / clip.w;
#if MAP_KIND == 1
  float ref = perspective_depth(dot(q - map_eye, map_forward) - depth_offset * texel);
#else
  float ref = 0.5 * ndc.z + 0.5 - depth_offset * texel / (map_far - map_near);
#endif
  vec2 uv = 0.5 * ndc.xy + 0.5;
  for (int i = -pcf_radius; i <= pcf_radius; ++i)
    for (int j = -pcf_radius; j <= pcf_radius; ++j)
      lit += texture(flat_map, vec3(uv + vec2(float(i), float(j)) / map_size, ref));
  lit /= float((2 * pcf_radius + 1) * (2 * pcf_radius + 1));
  bool inside = clip.w > 0.0 && all(lessThanEqual(abs(ndc.xy), vec2(1.0)));
  return inside ? lit : 1.0;
#endif
}
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position = texelFetch(surface_position, pixel, 0);
  vec4 gnormal = texelFetch(surface_gnormal, pixel, 0);
  // The background and other cascades' pixels come in whole regions of the
  // image: skipping them skips whole blocks of fragments.
  if (position.w < 0.5 || gnormal.w < distance_range.x || gnormal.w >= distance_range.y) {
    color = vec4(0.0);
    return;
  }
  vec3 n = texelFetch(surface_normal, pixel, 0).xyz;
  vec3 ng = gnormal.xyz;
  vec3 dir;
  vec3 e = irradiance(position.xyz, n, dir);
  color = vec4(dot(dir, ng) > 0.0 ? e * (visibility(position.xyz, ng) / PI) : vec3(0.0), 1.0);
}
)";

// The thesis's modulation: the albedo texture times the light.
constexpr const char* kModulateFragment = R"(#version 330 core
uniform sampler2D albedo;
uniform sampler2D light;
out vec4 color;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  color = vec4(texelFetch(albedo, pixel, 0).rgb * texelFetch(light, pixel, 0).rgb, 1.0);
}
)";

GLuint compile_shader(GLenum type, const char* source, std::string& why) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    why = std::string("shader does not compile: ") + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

GLuint link_program(const char* vertex, const char* fragment, std::string& why) {
  const GLuint vs = compile_shader(GL_VERTEX_SHADER, vertex, why);
  const GLuint fs = vs ? compile_shader(GL_FRAGMENT_SHADER, fragment, why) : 0;
  if (!fs) {
    if (vs) glDeleteShader(vs);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    why = std::string("shader program does not link: ") + log;
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

// ---- matrices (column vectors, OpenGL clip space) ----

Mat4 look_at(const Vec3& eye, const Vec3& forward, const Vec3& up_hint) {
  const Vec3 f = forward.normalized();
  Vec3 up = up_hint;
  if (std::abs(f.dot(up.normalized())) > 0.99f) up = std::abs(f.z()) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
  const Vec3 s = f.cross(up).normalized();
  const Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Mat4 perspective(float fovy, float near, float far) {
  const float t = 1.0f / std::tan(fovy * 0.5f);
  Mat4 m = Mat4::Zero();
  m(0, 0) = t;
  m(1, 1) = t;
  m(2, 2) = -(far + near) / (far - near);
  m(2, 3) = -2.0f * far * near / (far - near);
  m(3, 2) = -1.0f;
  return m;
}

Mat4 orthographic(float left, float right, float bottom, float top, float near, float far) {
  Mat4 m = Mat4::Identity();
  m(0, 0) = 2.0f / (right - left);
  m(1, 1) = 2.0f / (top - bottom);
  m(2, 2) = -2.0f / (far - near);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

std::array<Vec3, 8> corners(const Eigen::AlignedBox3f& box) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = box.corner(Eigen::AlignedBox3f::CornerType(i));
  return c;
}

// One fixed sample of a light and the shadow map that goes with it.
struct LightSamplePoint {
  enum class Map { cube, perspective, orthographic } map = Map::cube;
  Vec3 eye = Vec3::Zero();      // where the map looks from
  Vec3 forward = Vec3::UnitZ(); // perspective: its axis
  Mat4 view_projection = Mat4::Identity();
  float near = 0.01f, far = 1.0f;
  float texel_per_depth = 0.0f, texel_world = 0.0f;
  Vec2 disc_offset = Vec2::Zero();  // point/spot
  Vec3 area_point = Vec3::Zero();   // area
  Vec3 sun_direction = Vec3::UnitZ();
  int side = 0;                       // of the map (of each cube face), texels
  float weight = 1.0f;                // its share of the light
  Vec2 distance_range = Vec2(0.0f, std::numeric_limits<float>::infinity());  // the pixels it serves
};

// A slice of the view by distance from the camera, for the sun's cascaded
// maps: each gets the detail its part of the image needs.
struct Cascade {
  float near = 0.0f, far = std::numeric_limits<float>::infinity();
  Eigen::AlignedBox3f box;  // what the view sees in it
};

}  // namespace

struct GlRelighter::State {
  std::unique_ptr<HeadlessContext> context;
  ShadowMapOptions options;
  int width = 0, height = 0;
  Eigen::AlignedBox3f mesh_box, view_box;
  std::vector<Cascade> cascades;
  GLuint mesh_vao = 0, mesh_vbo = 0, mesh_ebo = 0, screen_vao = 0;
  GLsizei index_count = 0;
  GLuint position_tex = 0, normal_tex = 0, gnormal_tex = 0, albedo_tex = 0;
  GLuint flat_depth = 0, sun_depth = 0, cube_depth = 0, shadow_fbo = 0;
  GLuint light_tex = 0, light_fbo = 0, out_tex = 0, out_fbo = 0;
  GLuint depth_program = 0, modulate_program = 0;
  std::map<std::tuple<int, int, int, bool>, GLuint> shade_programs;
  std::vector<float> readback;

  ~State() {
    if (!context) return;
    HeadlessContext::Current current(*context);
    const GLuint textures[] = {position_tex, normal_tex, gnormal_tex, albedo_tex, flat_depth,
                               sun_depth,    cube_depth, light_tex,   out_tex};
    glDeleteTextures(9, textures);
    const GLuint framebuffers[] = {shadow_fbo, light_fbo, out_fbo};
    glDeleteFramebuffers(3, framebuffers);
    const GLuint buffers[] = {mesh_vbo, mesh_ebo};
    glDeleteBuffers(2, buffers);
    const GLuint arrays[] = {mesh_vao, screen_vao};
    glDeleteVertexArrays(2, arrays);
    glDeleteProgram(depth_program);
    for (const auto& [key, program] : shade_programs) glDeleteProgram(program);
    glDeleteProgram(modulate_program);
  }

  int cube_size() const { return std::max(16, options.size / 2); }
  GLuint flat_map_of(const LightSamplePoint& s) const {
    return s.map == LightSamplePoint::Map::orthographic ? sun_depth : flat_depth;
  }
  float scene_size() const { return std::max(1e-3f, (mesh_box.max() - mesh_box.min()).norm()); }

  std::vector<LightSamplePoint> samples_of(const Light& light) const;
  LightSamplePoint cube_sample(const Vec3& eye) const;
  LightSamplePoint perspective_sample(const Vec3& eye, const Vec3& forward, float fovy) const;
  LightSamplePoint orthographic_sample(const Vec3& towards_light, const Cascade& cascade) const;
  void render_shadow_map(const LightSamplePoint& sample);
  GLuint shade_program(int light_type, int map_kind, int pcf_radius, bool extended);
  void shade(const Light& light, const Vec3& emission, const LightSamplePoint& sample, bool add);
  void add_light(const Light& light, const Vec3& emission, bool first);
  void read(GLuint fbo, Image& out);
};

// ---- light samples and their maps ----

LightSamplePoint GlRelighter::State::cube_sample(const Vec3& eye) const {
  LightSamplePoint s;
  s.map = LightSamplePoint::Map::cube;
  s.eye = eye;
  float far = 0.0f;
  for (const Vec3& c : corners(mesh_box)) far = std::max(far, (c - eye).cwiseAbs().maxCoeff());
  s.far = std::max(far * 1.01f, 1e-3f);
  s.near = std::max(1e-4f, 1e-4f * scene_size());
  s.side = cube_size();
  s.texel_per_depth = 2.0f / float(s.side);
  return s;
}

LightSamplePoint GlRelighter::State::perspective_sample(const Vec3& eye, const Vec3& forward, float fovy) const {
  LightSamplePoint s;
  s.map = LightSamplePoint::Map::perspective;
  s.eye = eye;
  s.forward = forward.normalized();
  float far = 0.0f;
  for (const Vec3& c : corners(mesh_box)) far = std::max(far, (c - eye).norm());
  s.far = std::max(far * 1.01f, 1e-3f);
  s.near = std::max(1e-4f, 1e-4f * scene_size());
  s.view_projection = perspective(fovy, s.near, s.far) * look_at(eye, s.forward, Vec3(0, 0, 1));
  s.side = options.size;
  s.texel_per_depth = 2.0f * std::tan(fovy * 0.5f) / float(s.side);
  return s;
}

// The sun's map: along its direction, over what the view sees, deep enough
// to hold every occluder of the scene.
LightSamplePoint GlRelighter::State::orthographic_sample(const Vec3& towards_light, const Cascade& cascade) const {
  LightSamplePoint s;
  s.map = LightSamplePoint::Map::orthographic;
  s.sun_direction = towards_light.normalized();
  s.distance_range = Vec2(cascade.near, cascade.far);
  const Eigen::AlignedBox3f& view_box = cascade.box;
  const Vec3 center = view_box.center();
  const Mat4 view = look_at(center, -s.sun_direction, Vec3(0, 0, 1));
  Eigen::AlignedBox3f seen, all;
  for (const Vec3& c : corners(view_box)) seen.extend((view * c.homogeneous()).head<3>());
  for (const Vec3& c : corners(mesh_box)) all.extend((view * c.homogeneous()).head<3>());
  const float margin = 1e-3f * scene_size();
  const float side = std::max(seen.max().x() - seen.min().x(), seen.max().y() - seen.min().y()) + 2 * margin;
  const Vec2 mid = 0.5f * (seen.min() + seen.max()).head<2>();
  // Looking down -z: depth runs from -max z (nearest the sun) to -min z.
  s.near = -all.max().z() - margin;
  s.far = -all.min().z() + margin;
  s.view_projection = orthographic(mid.x() - side / 2, mid.x() + side / 2, mid.y() - side / 2, mid.y() + side / 2,
                                   s.near, s.far) *
                      view;
  s.side = options.sun_size;
  s.texel_world = side / float(s.side);
  return s;
}

// The fixed samples a light is drawn with: one for a light without extent,
// options.soft_samples spread over its disc, rectangle or cone otherwise —
// but a sun of at most 1 degree is drawn from its centre: its penumbra, under
// 2 cm per metre between occluder and receiver, is narrower than the blur of
// the filtering. The sun's maps come in cascades.
std::vector<LightSamplePoint> GlRelighter::State::samples_of(const Light& light) const {
  const bool extended = LightSampler(light).needs_random() &&
                        !(light.type == LightType::directional && light.angle_deg <= 1.0f);
  const int n = extended ? std::max(1, options.soft_samples) : 1;
  std::vector<LightSamplePoint> samples;
  for (int i = 0; i < n; ++i) {
    const Vec2 u = extended ? hammersley(i, n) : Vec2(0.5f, 0.5f);
    switch (light.type) {
      case LightType::point:
      case LightType::spot: {
        // The disc faces each lit point; the maps look from points of a disc
        // facing the middle of the view.
        const Vec2 offset = light.radius > 0.0f ? Vec2(sample_concentric_disc(u) * light.radius) : Vec2::Zero();
        Vec3 t, b;
        orthonormal_basis((view_box.center() - light.position).normalized(), t, b);
        const Vec3 eye = light.position + offset.x() * t + offset.y() * b;
        const float fovy = radians(light.spot_angle_deg) * 1.05f + 0.02f;
        LightSamplePoint s = (light.type == LightType::spot && fovy < radians(160.0f))
                                 ? perspective_sample(eye, light.direction, fovy)
                                 : cube_sample(eye);
        s.disc_offset = offset;
        samples.push_back(s);
        break;
      }
      case LightType::area: {
        const Vec3 normal = light.direction.normalized();
        const Vec3 side_w = normal.cross(light.up).normalized(), side_h = side_w.cross(normal);
        const Vec3 q = light.position + (u.x() - 0.5f) * light.size.x() * side_w +
                       (u.y() - 0.5f) * light.size.y() * side_h;
        // A perspective map along the light's normal, wide enough for what the view sees.
        float half = radians(5.0f);
        for (const Vec3& c : corners(view_box)) {
          const Vec3 d = c - q;
          if (d.dot(normal) > 0.0f) half = std::max(half, std::acos(std::clamp(d.normalized().dot(normal), -1.0f, 1.0f)));
        }
        LightSamplePoint s = perspective_sample(q, normal, std::min(2.0f * half + 0.05f, radians(160.0f)));
        s.area_point = q;
        samples.push_back(s);
        break;
      }
      case LightType::directional: {
        const Vec3 to_sun = -light.direction.normalized();
        const Vec3 d = light.angle_deg > 0.0f
                           ? to_world(sample_uniform_cone(u, std::cos(radians(light.angle_deg) * 0.5f)), to_sun)
                           : to_sun;
        for (const Cascade& cascade : cascades) samples.push_back(orthographic_sample(d, cascade));
        break;
      }
    }
  }
  // Cascades split the pixels between them; samples share the light.
  for (LightSamplePoint& s : samples) s.weight = 1.0f / float(n);
  return samples;
}

// ---- rendering ----

void GlRelighter::State::render_shadow_map(const LightSamplePoint& s) {
  glUseProgram(depth_program);
  const GLint vp = glGetUniformLocation(depth_program, "view_projection");
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glBindVertexArray(mesh_vao);
  if (s.map == LightSamplePoint::Map::cube) {
    // OpenGL's cube faces: +x, -x, +y, -y, +z, -z, each with its up.
    static const Vec3 forward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const Vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    glViewport(0, 0, s.side, s.side);
    const Mat4 projection = perspective(kPi / 2, s.near, s.far);
    for (int face = 0; face < 6; ++face) {
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, cube_depth, 0);
      glClear(GL_DEPTH_BUFFER_BIT);
      const Mat4 m = projection * look_at(s.eye, forward[face], up[face]);
      glUniformMatrix4fv(vp, 1, GL_FALSE, m.data());
      glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
    }
  } else {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, flat_map_of(s), 0);
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
    const std::string source = "#version 330 core\n#define LIGHT_TYPE " + std::to_string(light_type) +
                               "\n#define MAP_KIND " + std::to_string(map_kind) + "\n#define PCF_RADIUS " +
                               std::to_string(pcf_radius) + "\n#define EXTENDED " + (extended ? "1" : "0") +
                               "\n" + kShadeFragment;
    std::string why;
    program = link_program(kScreenVertex, source.c_str(), why);
    if (!program) throw std::runtime_error("OpenGL backend: " + why);
  }
  return program;
}

// add: blend onto what the framebuffer holds (else overwrite it).
void GlRelighter::State::shade(const Light& light, const Vec3& emission, const LightSamplePoint& s, bool add) {
  const int type = light.type == LightType::point ? 0 : light.type == LightType::spot ? 1
                   : light.type == LightType::area  ? 2
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
  for (const LightSamplePoint& s : samples_of(light)) {
    render_shadow_map(s);
    shade(light, emission * s.weight, s, !first);
    first = false;
  }
}

void GlRelighter::State::read(GLuint fbo, Image& out) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  readback.resize(size_t(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, readback.data());
  if (out.width != width || out.height != height) out = Image(width, height);
  // Framebuffer row y holds view row y (the textures were uploaded top row first).
  for (size_t i = 0; i < out.size(); ++i) out.pixels[i] = Vec3(readback[4 * i], readback[4 * i + 1], readback[4 * i + 2]);
}

// ---- setup ----

namespace {

GLuint float_texture(int width, int height, GLenum internal_format, GLenum format, const float* data) {
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexImage2D(GL_TEXTURE_2D, 0, GLint(internal_format), width, height, 0, format, GL_FLOAT, data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return tex;
}

// n cascades holding equal shares of the pixels that see a surface: as much
// detail for the far part of the view as it takes in the image.
std::vector<Cascade> view_cascades(const PixelSurfaces& surfaces, int n) {
  std::vector<float> distances;
  for (size_t i = 0; i < surfaces.surface.size(); ++i)
    if (surfaces.hit[i]) distances.push_back(surfaces.surface[i].distance);
  std::sort(distances.begin(), distances.end());
  std::vector<Cascade> cascades(distances.empty() ? 1 : size_t(n));
  for (int c = 1; c < int(cascades.size()); ++c)
    cascades[c].near = cascades[c - 1].far = distances[distances.size() * size_t(c) / size_t(n)];
  for (size_t i = 0; i < surfaces.surface.size(); ++i) {
    if (!surfaces.hit[i]) continue;
    const SurfacePoint& s = surfaces.surface[i];
    for (Cascade& c : cascades)
      if (s.distance >= c.near && s.distance < c.far) c.box.extend(s.position);
  }
  for (Cascade& c : cascades)
    if (c.box.isEmpty()) c.box.extend(Vec3::Zero());
  return cascades;
}

void set_shadow_sampling(GLenum target) {
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

}  // namespace

std::unique_ptr<GlRelighter> GlRelighter::open(const TriangleMesh& mesh, const PixelSurfaces& surfaces,
                                               const Image& albedo_coverage, const ShadowMapOptions& options,
                                               std::string& why) {
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
  state->mesh_box = mesh.bounds();

  state->depth_program = link_program(kDepthVertex, kDepthFragment, why);
  state->modulate_program = state->depth_program ? link_program(kScreenVertex, kModulateFragment, why) : 0;
  if (!state->modulate_program) return nullptr;
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

  // The view: what each pixel sees, and the albedo, as textures (top row first).
  std::vector<float> position(size_t(w) * h * 4, 0.0f), normal(size_t(w) * h * 3), gnormal(size_t(w) * h * 4),
      albedo(size_t(w) * h * 3);
  for (size_t i = 0; i < surfaces.surface.size(); ++i) {
    const SurfacePoint& s = surfaces.surface[i];
    if (surfaces.hit[i]) {
      for (int c = 0; c < 3; ++c) position[4 * i + c] = s.position[c];
      position[4 * i + 3] = 1.0f;
      state->view_box.extend(s.position);
    }
    for (int c = 0; c < 3; ++c) {
      normal[3 * i + c] = s.normal[c];
      gnormal[4 * i + c] = s.geometric_normal[c];
      albedo[3 * i + c] = albedo_coverage.pixels[i][c];
    }
    gnormal[4 * i + 3] = s.distance;
  }
  if (state->view_box.isEmpty()) state->view_box = state->mesh_box;
  state->cascades = view_cascades(surfaces, std::max(1, options.sun_cascades));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  state->position_tex = float_texture(w, h, GL_RGBA32F, GL_RGBA, position.data());
  state->normal_tex = float_texture(w, h, GL_RGB32F, GL_RGB, normal.data());
  state->gnormal_tex = float_texture(w, h, GL_RGBA32F, GL_RGBA, gnormal.data());
  state->albedo_tex = float_texture(w, h, GL_RGB32F, GL_RGB, albedo.data());

  // Shadow maps: a perspective one, the sun's, a cube, reused by every light sample.
  for (auto [tex, size] : {std::pair{&state->flat_depth, state->options.size},
                           std::pair{&state->sun_depth, state->options.sun_size}}) {
    glGenTextures(1, tex);
    glBindTexture(GL_TEXTURE_2D, *tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    set_shadow_sampling(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  const int cube = state->cube_size();
  glGenTextures(1, &state->cube_depth);
  glBindTexture(GL_TEXTURE_CUBE_MAP, state->cube_depth);
  for (int face = 0; face < 6; ++face)
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_DEPTH_COMPONENT32F, cube, cube, 0, GL_DEPTH_COMPONENT,
                 GL_FLOAT, nullptr);
  set_shadow_sampling(GL_TEXTURE_CUBE_MAP);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  glGenFramebuffers(1, &state->shadow_fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, state->shadow_fbo);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);

  // The light accumulates in a float framebuffer; the re-lit image in another.
  for (auto [tex, fbo] : {std::pair{&state->light_tex, &state->light_fbo}, std::pair{&state->out_tex, &state->out_fbo}}) {
    *tex = float_texture(w, h, GL_RGBA32F, GL_RGBA, nullptr);
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      why = "a float framebuffer is not supported";
      return nullptr;
    }
  }
  glDisable(GL_CULL_FACE);  // both sides of every surface cast shadows
  if (glGetError() != GL_NO_ERROR) {
    why = "OpenGL error while setting up";
    return nullptr;
  }
  spdlog::info("OpenGL backend: {} ({})", state->context->renderer(), state->context->version());
  return std::unique_ptr<GlRelighter>(new GlRelighter(std::move(state)));
}

GlRelighter::GlRelighter(std::unique_ptr<State> state) : state_(std::move(state)) {}
GlRelighter::~GlRelighter() = default;

const std::string& GlRelighter::renderer() const { return state_->context->renderer(); }

namespace {

// Binds the view's textures and the shadow maps to their units.
void bind_textures(GLuint position, GLuint normal, GLuint gnormal, GLuint cube, GLuint flat) {
  const std::pair<GLenum, GLuint> units[] = {{GL_TEXTURE_2D, position}, {GL_TEXTURE_2D, normal},
                                             {GL_TEXTURE_2D, gnormal},  {GL_TEXTURE_CUBE_MAP, cube},
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

Image GlRelighter::relight(const std::vector<Light>& lights) {
  State& s = *state_;
  HeadlessContext::Current current(*s.context);
  bind_textures(s.position_tex, s.normal_tex, s.gnormal_tex, s.cube_depth, s.flat_depth);
  glBindFramebuffer(GL_FRAMEBUFFER, s.light_fbo);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  bool first = true;
  for (const Light& light : lights)
    if (light.enabled && !light.emission().isZero()) {
      s.add_light(light, light.emission(), first);
      first = false;
    }

  glUseProgram(s.modulate_program);
  glUniform1i(glGetUniformLocation(s.modulate_program, "albedo"), 0);
  glUniform1i(glGetUniformLocation(s.modulate_program, "light"), 1);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, s.albedo_tex);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, s.light_tex);
  glBindFramebuffer(GL_FRAMEBUFFER, s.out_fbo);
  glViewport(0, 0, s.width, s.height);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(s.screen_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  Image out;
  s.read(s.out_fbo, out);
  return out;
}

}  // namespace relight
