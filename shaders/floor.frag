#version 330 core
// A light floor with a metric grid: thin lines every centimetre, stronger ones every 10 cm,
// both faded out where they would alias, and fog into the background towards the horizon.
in vec3 worldPosition;

uniform vec3 eye;
uniform float fogStart;
uniform float fogEnd;
uniform vec3 backgroundSrgb;
uniform vec3 lightDirection;

out vec4 fragColour;

// Coverage of grid lines of the given spacing and width (metres) at this pixel. Lines thinner
// than a pixel are drawn one pixel wide and proportionally fainter, so they neither vanish nor
// alias; where a cell shrinks to a few pixels the grid would shimmer, so it fades out.
float gridLines(vec2 xz, float spacing, float width) {
  vec2 distanceToLine = abs(fract(xz / spacing - 0.5) - 0.5) * spacing;
  vec2 pixel = max(fwidth(xz), vec2(1e-7));
  vec2 halfWidth = max(vec2(0.5 * width), 0.5 * pixel);
  vec2 strength = min(vec2(width) / pixel, vec2(1.0));
  vec2 coverage = strength * (1.0 - smoothstep(halfWidth - 0.5 * pixel, halfWidth + 0.5 * pixel, distanceToLine));
  float visible = 1.0 - smoothstep(0.12, 0.3, max(pixel.x, pixel.y) / spacing);
  return max(coverage.x, coverage.y) * visible;
}

vec3 toLinear(vec3 srgb) {
  return mix(srgb / 12.92, pow((srgb + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), srgb));
}

vec3 toSrgb(vec3 linear) {
  vec3 low = linear * 12.92;
  vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
  return mix(low, high, step(vec3(0.0031308), linear));
}

void main() {
  vec2 xz = worldPosition.xz;
  vec3 albedo = vec3(0.26, 0.27, 0.29);
  albedo = mix(albedo, vec3(0.36, 0.37, 0.39), gridLines(xz, 0.01, 0.0005));
  albedo = mix(albedo, vec3(0.46, 0.48, 0.51), gridLines(xz, 0.10, 0.0012));
  vec3 linear = albedo * (0.45 + 0.6 * max(lightDirection.y, 0.0));
  float fog = smoothstep(fogStart, fogEnd, length(worldPosition - eye));
  linear = mix(linear, toLinear(backgroundSrgb), fog);
  fragColour = vec4(toSrgb(clamp(linear, 0.0, 1.0)), 1.0);
}
