#version 330 core
// The floor: the metric grid tile (render/floor_tile.cpp, already lit and in sRGB) repeated
// every 10 cm, its mipmaps fading the lines with distance, and fog into the background colour
// towards the horizon.
in vec3 worldPosition;

uniform sampler2D gridTile;
uniform float tileMetres;
uniform vec3 eye;
uniform float fogStart;
uniform float fogEnd;
uniform vec3 backgroundSrgb;

out vec4 fragColour;

void main() {
  vec3 floorColour = texture(gridTile, worldPosition.xz / tileMetres).rgb;
  float fog = smoothstep(fogStart, fogEnd, length(worldPosition - eye));
  fragColour = vec4(mix(floorColour, backgroundSrgb, fog), 1.0);
}
