#pragma once
// Renderer's insides, shared by renderer.cpp (which makes the GL objects) and renderer_passes.cpp
// (which draws each frame with them). Only those two include it: callers of Renderer need no GL.

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "render/camera.h"
#include "render/gl_context.h"
#include "render/gl_handles.h"
#include "render/overlay_text.h"
#include "render/renderer.h"
#include "render/shader_program.h"

namespace coinroll::render {

// Key light, pointing from the scene towards the light: high and slightly behind the default
// camera's left shoulder, so the shadow falls forward-right and the face catches a highlight.
inline const glm::vec3 kLightDirection = glm::normalize(glm::vec3(-0.35f, 1.0f, 0.45f));

// A floor decal's square: [-1/2, 1/2] along x and z, scaled and turned per frame.
inline const std::vector<glm::vec3> kUnitFloorSquare = {{-0.5f, 0, -0.5f}, {0.5f, 0, 0.5f},  {0.5f, 0, -0.5f},
                                                        {-0.5f, 0, -0.5f}, {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}};

template <class Vertex>
void upload(const GlFunctions& gl, GLuint buffer, const std::vector<Vertex>& vertices, GLenum usage) {
  gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(), usage);
}

struct Renderer::GlState {
  explicit GlState(std::unique_ptr<GlContext> made) : context(std::move(made)) {}

  std::unique_ptr<GlContext> context;  // first member: created first, destroyed after every GL object below
  const GlFunctions& gl = context->functions();
  Framebuffer drawTarget, resolveTarget;
  Renderbuffer drawColour, drawDepthStencil, resolveColour;
  ShaderProgram coinProgram{gl, "coin.vert", "coin.frag"};
  ShaderProgram floorProgram{gl, "floor.vert", "floor.frag"};
  ShaderProgram flatProgram{gl, "flat.vert", "flat.frag"};
  ShaderProgram traceProgram{gl, "trace.vert", "trace.frag"};
  ShaderProgram hudProgram{gl, "hud.vert", "hud.frag"};
  std::optional<ShaderProgram> fxaaProgram;  // only for Antialiasing::Fxaa
  Texture sceneColour;                       // the FXAA pass reads the scene from this texture
  // Ssaa with MSAA: the drawn picture with its samples resolved, still at the drawn size.
  Framebuffer supersampleTarget;
  Renderbuffer supersampleColour;
  VertexArray coinArray = makeVertexArray(gl), floorArray = makeVertexArray(gl), markerArray = makeVertexArray(gl),
              traceArray = makeVertexArray(gl), hudArray = makeVertexArray(gl), fullScreenArray = makeVertexArray(gl),
              scaleBarArray = makeVertexArray(gl);
  Buffer coinBuffer = makeBuffer(gl), floorBuffer = makeBuffer(gl), markerBuffer = makeBuffer(gl),
         traceBuffer = makeBuffer(gl), hudBuffer = makeBuffer(gl), scaleBarBuffer = makeBuffer(gl);
  Texture coinFace = makeTexture(gl);
  Texture floorGrid = makeTexture(gl);
  Texture glyphs = makeTexture(gl);
  std::optional<GlyphAtlas> atlas;  // made once, at the picture's text size
  GLsizei coinVertices = 0, markerVertices = 0;
  // The draw target's colour, depth and stencil just after the floor, for the camera it was
  // drawn with; a blit of the same format and sample count restores it exactly.
  Framebuffer backgroundCache;
  Renderbuffer backgroundColour, backgroundDepthStencil;
  std::optional<CameraView> backgroundCamera, previousCamera;
};

}  // namespace coinroll::render
