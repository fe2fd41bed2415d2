#version 330 core
// Coloured by time (deep blue for old, orange-red for new) and fading with age, so the
// direction of travel and the recent path both read.
in float vertexAge;
out vec4 fragColour;

void main() {
  vec3 recent = vec3(0.93, 0.33, 0.08);
  vec3 old = vec3(0.30, 0.52, 0.95);
  fragColour = vec4(mix(recent, old, vertexAge), mix(0.95, 0.25, vertexAge));
}
