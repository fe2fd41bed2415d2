#version 330 core
// A brass obverse with blue enamel, a silver reverse with red (so spin and a flip both read at a
// glance), both carrying the pattern of assets/coin_face.png, and a knurled rim. Blinn-Phong in
// linear light, sRGB out.
in vec3 worldPosition;
in vec3 worldNormal;
in vec3 bodyPosition;
flat in int surface;

uniform vec3 eye;
uniform vec3 lightDirection;
uniform float radius;
uniform float opacity;
uniform vec4 tint;  // rgb, and how much of it replaces the metal's colour (a strobe copy's age)
uniform sampler2D face;

out vec4 fragColour;

const int kFrontFace = 0;
const int kBackFace = 1;
const int kOuterRim = 2;

// 1 inside the region where `distanceOutside` < 0, with a one-pixel soft edge.
float inside(float distanceOutside) {
  float width = fwidth(distanceOutside);
  return 1.0 - smoothstep(-width, width, distanceOutside);
}

// assets/coin_face.png: red is the metal's relief shading, green where the enamel goes.
vec3 faceColour(vec3 metal, vec3 enamel) {
  vec2 p = bodyPosition.xy / radius;
  vec2 pattern = texture(face, vec2(0.5 + 0.5 * p.x, 0.5 - 0.5 * p.y)).rg;
  return mix(metal * pattern.r, enamel, pattern.g);
}

vec3 rimColour(vec3 metal) {
  float turns = atan(bodyPosition.y, bodyPosition.x) / 6.2831853;
  float stripe = abs(fract(turns * 96.0) - 0.5) - 0.25;  // 96 knurls around the rim
  return mix(metal, metal * 0.55, inside(stripe));
}

vec3 toSrgb(vec3 linear) {
  vec3 low = linear * 12.92;
  vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
  return mix(low, high, step(vec3(0.0031308), linear));
}

void main() {
  vec3 brass = vec3(0.80, 0.56, 0.20);
  vec3 silver = vec3(0.48, 0.50, 0.55);
  vec3 albedo;
  if (surface == kFrontFace) albedo = faceColour(brass, vec3(0.03, 0.07, 0.32));
  else if (surface == kBackFace) albedo = faceColour(silver, vec3(0.36, 0.03, 0.03));
  else if (surface == kOuterRim) albedo = rimColour(brass);
  else albedo = brass * 0.7;
  albedo = mix(albedo, tint.rgb, tint.a);

  vec3 n = normalize(worldNormal);
  vec3 v = normalize(eye - worldPosition);
  vec3 h = normalize(lightDirection + v);
  vec3 ambient = mix(vec3(0.20, 0.19, 0.17), vec3(0.38, 0.42, 0.48), 0.5 + 0.5 * n.y);
  float diffuse = max(dot(n, lightDirection), 0.0);
  float specular = pow(max(dot(n, h), 0.0), 40.0) * step(0.0, dot(n, lightDirection));
  vec3 linear = albedo * (ambient + 0.85 * diffuse) + 0.45 * specular * mix(albedo, vec3(1.0), 0.3);
  fragColour = vec4(toSrgb(clamp(linear, 0.0, 1.0)), opacity);
}
