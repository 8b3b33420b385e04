// shade.glsl as a compute shader, a thread per view pixel, added to the light
// the image holds (accumulate) or replacing it. Where the driver offers
// compute shaders (OpenGL 4.3) they run on every core of the GPU, where a
// fragment shader may get only its graphics units (a data-centre GPU's few).
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform image2D light_image;
uniform bool accumulate;
void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(light_image)))) return;
  vec4 color = shade_pixel(pixel);
  if (accumulate) color += imageLoad(light_image, pixel);
  imageStore(light_image, pixel, color);
}
