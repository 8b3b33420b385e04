// shade.glsl as a fragment shader over a triangle covering the framebuffer
// (screen.vert), blended onto the light the framebuffer holds.
out vec4 color;
void main() { color = shade_pixel(ivec2(gl_FragCoord.xy)); }
