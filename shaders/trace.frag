#version 330 core
// Coloured by time (deep blue for old, orange-red for new) and fading with age, so the
// direction of travel and the recent path both read; where the coin slid, yellow fading to pale
// green instead, so the stretches of sliding stand out from the rolling ones at any age.
in float vertexAge;
in float vertexSliding;
out vec4 fragColour;

void main() {
  vec3 recent = mix(vec3(0.93, 0.33, 0.08), vec3(0.98, 0.84, 0.10), vertexSliding);
  vec3 old = mix(vec3(0.30, 0.52, 0.95), vec3(0.55, 0.90, 0.55), vertexSliding);
  fragColour = vec4(mix(recent, old, vertexAge), mix(0.95, 0.25, vertexAge));
}
