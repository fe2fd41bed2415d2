#version 330 core
// Overlay text and panels in pixel coordinates (origin top-left), textured from the glyph atlas.
layout(location = 0) in vec2 pixel;
layout(location = 1) in vec2 texel;
layout(location = 2) in vec4 colour;

uniform vec2 viewportSize;
uniform vec2 atlasSize;  // texels

out vec2 atlasPosition;
out vec4 vertexColour;

void main() {
  atlasPosition = texel / atlasSize;
  vertexColour = colour;
  vec2 ndc = vec2(2.0 * pixel.x / viewportSize.x - 1.0, 1.0 - 2.0 * pixel.y / viewportSize.y);
  gl_Position = vec4(ndc, 0.0, 1.0);
}
