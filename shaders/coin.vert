#version 330 core
// The coin in its body frame (coin plane = body XY, normal = body Z), placed by its pose.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in float part;

uniform mat4 model;
uniform mat3 normalMatrix;
uniform mat4 viewProjection;

out vec3 worldPosition;
out vec3 worldNormal;
out vec3 bodyPosition;
flat out int surface;

void main() {
  vec4 world = model * vec4(position, 1.0);
  worldPosition = world.xyz;
  worldNormal = normalMatrix * normal;
  bodyPosition = position;
  surface = int(part + 0.5);
  gl_Position = viewProjection * world;
}
