#version 330 core
// One triangle that covers the viewport, from gl_VertexID alone (no vertex buffer).
out vec2 uv;

void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);  // (0,0), (2,0), (0,2)
  uv = corner;
  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
