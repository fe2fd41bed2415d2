#version 330 core
// The contact-point trace: a ribbon on the floor, each vertex carrying its age (0 newest, 1 oldest)
// and whether the coin slid there (1) or rolled (0).
layout(location = 0) in vec2 position;
layout(location = 1) in float age;
layout(location = 2) in float sliding;

uniform mat4 viewProjection;

out float vertexAge;
out float vertexSliding;

void main() {
  vertexAge = age;
  vertexSliding = sliding;
  gl_Position = viewProjection * vec4(position.x, 0.0, position.y, 1.0);
}
