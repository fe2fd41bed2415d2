#version 330 core
// Overlay text in pixel coordinates (origin top-left).
layout(location = 0) in vec2 pixel;
layout(location = 1) in vec4 colour;

uniform vec2 viewportSize;

out vec4 vertexColour;

void main() {
  vertexColour = colour;
  vec2 ndc = vec2(2.0 * pixel.x / viewportSize.x - 1.0, 1.0 - 2.0 * pixel.y / viewportSize.y);
  gl_Position = vec4(ndc, 0.0, 1.0);
}
