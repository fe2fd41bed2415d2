#version 330 core
// Coloured by time and fading with age, so the direction of travel and the recent path both read;
// where the coin slid, in a second pair of colours, so the stretches of sliding stand out from the
// rolling ones at any age. The colours are the theme's (render/theme.cpp).
in float vertexAge;
in float vertexSliding;

uniform vec3 recentRolling;
uniform vec3 oldRolling;
uniform vec3 recentSliding;
uniform vec3 oldSliding;
uniform vec2 opacity;  // newest, oldest

out vec4 fragColour;

void main() {
  // Where the coin was in the air (render/meshes.h kTraceInTheAir) there is no contact to trace.
  if (vertexSliding > 1.5) discard;
  vec3 recent = mix(recentRolling, recentSliding, vertexSliding);
  vec3 old = mix(oldRolling, oldSliding, vertexSliding);
  fragColour = vec4(mix(recent, old, vertexAge), mix(opacity.x, opacity.y, vertexAge));
}
