#version 330 core
// A square of half-size `extent` around `centre` on the floor plane y = 0.
layout(location = 0) in vec2 corner;

uniform mat4 viewProjection;
uniform vec2 centre;
uniform float extent;

out vec3 worldPosition;

void main() {
  vec2 xz = centre + extent * corner;
  worldPosition = vec3(xz.x, 0.0, xz.y);
  gl_Position = viewProjection * vec4(worldPosition, 1.0);
}
