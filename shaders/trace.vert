#version 330 core
// The contact-point trace: a ribbon on the floor, each vertex carrying its age (0 newest, 1 oldest).
layout(location = 0) in vec2 position;
layout(location = 1) in float age;

uniform mat4 viewProjection;

out float vertexAge;

void main() {
  vertexAge = age;
  gl_Position = viewProjection * vec4(position.x, 0.0, position.y, 1.0);
}
