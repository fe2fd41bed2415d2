#version 330 core
uniform vec4 colour;  // sRGB, straight alpha
out vec4 fragColour;
void main() { fragColour = colour; }
