#version 330 core
// Fast approximate anti-aliasing after Lottes (FXAA, 2009): find where luma changes sharply,
// estimate the edge's direction from the luma of the four diagonal neighbours, and average a
// few samples along that direction. Where the wider average overshoots the local luma range
// (it crossed into another edge), the narrower one is used instead.
in vec2 uv;

uniform sampler2D scene;
uniform vec2 texelSize;

out vec4 fragColour;

const float kSpanMax = 8.0;          // texels: the longest blur along an edge
const float kReduceMultiplier = 1.0 / 8.0;
const float kReduceMinimum = 1.0 / 128.0;

float luma(vec3 srgb) { return dot(srgb, vec3(0.299, 0.587, 0.114)); }

void main() {
  vec3 centre = texture(scene, uv).rgb;
  float lumaNW = luma(texture(scene, uv + vec2(-1.0, -1.0) * texelSize).rgb);
  float lumaNE = luma(texture(scene, uv + vec2(1.0, -1.0) * texelSize).rgb);
  float lumaSW = luma(texture(scene, uv + vec2(-1.0, 1.0) * texelSize).rgb);
  float lumaSE = luma(texture(scene, uv + vec2(1.0, 1.0) * texelSize).rgb);
  float lumaM = luma(centre);
  float lumaMin = min(lumaM, min(min(lumaNW, lumaNE), min(lumaSW, lumaSE)));
  float lumaMax = max(lumaM, max(max(lumaNW, lumaNE), max(lumaSW, lumaSE)));

  // The luma gradient is across the edge; its perpendicular runs along it.
  vec2 along = vec2(-((lumaNW + lumaNE) - (lumaSW + lumaSE)), (lumaNW + lumaSW) - (lumaNE + lumaSE));
  float reduce = max((lumaNW + lumaNE + lumaSW + lumaSE) * 0.25 * kReduceMultiplier, kReduceMinimum);
  float scale = 1.0 / (min(abs(along.x), abs(along.y)) + reduce);
  along = clamp(along * scale, vec2(-kSpanMax), vec2(kSpanMax)) * texelSize;

  // Alpha is averaged with the colour: on a transparent background the colour is premultiplied, and
  // an edge's coverage must blur as its colour does. On an opaque one every alpha is 1.
  vec4 narrow = 0.5 * (texture(scene, uv + along * (1.0 / 3.0 - 0.5)) + texture(scene, uv + along * (2.0 / 3.0 - 0.5)));
  vec4 wide = 0.5 * narrow + 0.25 * (texture(scene, uv - 0.5 * along) + texture(scene, uv + 0.5 * along));
  float lumaWide = luma(wide.rgb);
  fragColour = (lumaWide < lumaMin || lumaWide > lumaMax) ? narrow : wide;
}
