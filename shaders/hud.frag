#version 330 core
// The glyph atlas holds coverage (render/overlay_text.h): it scales the colour's alpha, so the
// glyphs' anti-aliased edges blend over the picture. Panels sample a fully covered texel.
in vec2 atlasPosition;
in vec4 vertexColour;

uniform sampler2D atlas;

out vec4 fragColour;

void main() { fragColour = vec4(vertexColour.rgb, vertexColour.a * texture(atlas, atlasPosition).r); }
