#version 330 core
in vec4 vertexColour;
out vec4 fragColour;
void main() { fragColour = vertexColour; }
