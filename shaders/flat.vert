#version 330 core
// Geometry in one flat colour: the coin's shadow (model includes the projection onto the floor)
// and the contact marker.
layout(location = 0) in vec3 position;

uniform mat4 model;
uniform mat4 viewProjection;

void main() { gl_Position = viewProjection * model * vec4(position, 1.0); }
