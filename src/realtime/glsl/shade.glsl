// One light sample's direct light at each pixel's surface, times its shadow
// map's visibility: the radiometry of LightSampler (src/scene/light.cpp)
// for one fixed point on the light (or direction of the sun). Compiled for
// each light type, map kind, filter width and extent (LIGHT_TYPE, MAP_KIND,
// PCF_RADIUS, EXTENDED, defined with the #version line in front of this):
// a software rasteriser runs all the code it cannot rule out. A fragment
// shader (shade.frag) or a compute shader (shade.comp) follows it.
const int light_type = LIGHT_TYPE;    // 0 point, 1 spot, 2 area, 3 sun
const int pcf_radius = PCF_RADIUS;
uniform sampler2D surface_position;   // xyz; w = 1 where the pixel sees a surface
uniform sampler2D surface_normal;     // shading normal; w: SurfacePoint::lift
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
// The light at one view pixel (alpha 1 where it sees a surface this map serves).
vec4 shade_pixel(ivec2 pixel) {
  vec4 position = texelFetch(surface_position, pixel, 0);
  vec4 gnormal = texelFetch(surface_gnormal, pixel, 0);
  // The background and other cascades' pixels come in whole regions of the
  // image: skipping them skips whole blocks of pixels.
  if (position.w < 0.5 || gnormal.w < distance_range.x || gnormal.w >= distance_range.y) return vec4(0.0);
  vec4 normal_lift = texelFetch(surface_normal, pixel, 0);
  vec3 n = normal_lift.xyz;
  vec3 ng = gnormal.xyz;
  vec3 dir;
  vec3 e = irradiance(position.xyz, n, dir);
  // As the CPU's shadow rays (RayScene::shadow_ray): looked up from the
  // smooth surface the vertices' normals describe, with no test of the
  // facet's own normal.
  return vec4(e * (visibility(position.xyz + normal_lift.w * ng, ng) / PI), 1.0);
}
