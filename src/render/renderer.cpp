#include "render/renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include "render/assets.h"
#include "render/camera.h"
#include "render/floor_tile.h"
#include "render/gl_context.h"
#include "render/gl_handles.h"
#include "render/overlay_text.h"
#include "render/scale_bar.h"
#include "render/shader_program.h"
#include "render/theme.h"

namespace coinroll::render {

namespace {

constexpr int kCoinSegments = 128;
// Key light, pointing from the scene towards the light: high and slightly behind the default
// camera's left shoulder, so the shadow falls forward-right and the face catches a highlight.
const glm::vec3 kLightDirection = glm::normalize(glm::vec3(-0.35f, 1.0f, 0.45f));
const glm::vec4 kShadowColour(0.0f, 0.0f, 0.0f, 0.45f);
const glm::vec4 kContactColour(0.85f, 0.1f, 0.08f, 1.0f);

// A strobe copy's tint, linear: dark blue (oldest) through grey to yellow (newest), cividis' ends,
// rising in lightness so the copies read in order where they overlap, in grey print and for
// colour-blind readers.
glm::vec3 ghostColour(std::size_t age, std::size_t count) {
  const glm::vec3 oldest(0.0f, 0.05f, 0.45f), middle(0.22f, 0.22f, 0.24f), newest(0.95f, 0.80f, 0.02f);
  const float f = count > 1 ? static_cast<float>(age) / static_cast<float>(count - 1) : 1.0f;
  return f < 0.5f ? glm::mix(oldest, middle, 2.0f * f) : glm::mix(middle, newest, 2.0f * f - 1.0f);
}

void validate(const RenderSettings& s) {
  for (const auto& [field, side] : {std::pair{"width", s.width}, std::pair{"height", s.height}}) {
    if (side < kMinImageSide || side > kMaxImageSide) {
      throw std::invalid_argument(fmt::format("render.{}: must be {}..{} pixels, got {}", field, kMinImageSide, kMaxImageSide, side));
    }
  }
  if (!isMsaaSampleCount(s.msaa) && s.antialiasing == Antialiasing::Msaa) {
    throw std::invalid_argument(fmt::format("render.msaa: must be one of {} samples, got {}", fmt::join(kMsaaSampleCounts, ", "), s.msaa));
  }
  if (!(s.coin.radius > 0) || !(s.coin.thickness > 0) || !(s.coin.innerRadius >= 0 && s.coin.innerRadius < s.coin.radius)) {
    throw std::invalid_argument(fmt::format("coin: radius {} m, inner radius {} m and thickness {} m cannot be drawn",
                                            s.coin.radius, s.coin.innerRadius, s.coin.thickness));
  }
  // The fillet must fit the cross-section: at most half the thickness (a half-torus rim) and at
  // most the rim's width (the flat face then shrinks to the hole's edge or the centre).
  const float maxEdgeRadius = std::min(0.5f * s.coin.thickness, s.coin.radius - s.coin.innerRadius);
  if (!(s.coin.edgeRadius >= 0 && s.coin.edgeRadius <= maxEdgeRadius)) {
    throw std::invalid_argument(fmt::format("coin: edge radius {} m cannot be drawn: must be 0..{} m (at most half the "
                                            "thickness {} m and the width radius - inner radius {} m)",
                                            s.coin.edgeRadius, maxEdgeRadius, s.coin.thickness,
                                            s.coin.radius - s.coin.innerRadius));
  }
}

glm::mat4 modelMatrix(const CoinPose& pose) { return glm::translate(glm::mat4(1.0f), pose.centre) * glm::mat4_cast(pose.attitude); }

// Projects points onto the floor (y = lift) along the light direction: a planar shadow, exact for
// a flat receiver and far cheaper than a shadow map on a software rasteriser.
glm::mat4 floorShadowProjection(float lift) {
  const glm::vec3 l = kLightDirection;
  glm::mat4 m(1.0f);
  m[1] = glm::vec4(-l.x / l.y, 0.0f, -l.z / l.y, 0.0f);  // column y: x' = x - (l.x/l.y)(y - lift), ...
  m[3] = glm::vec4(l.x / l.y * lift, lift, l.z / l.y * lift, 1.0f);
  return m;
}

template <class Vertex>
void upload(const GlFunctions& gl, GLuint buffer, const std::vector<Vertex>& vertices, GLenum usage) {
  gl.BindBuffer(GL_ARRAY_BUFFER, buffer);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(), usage);
}

void uploadMipmapped(const GlFunctions& gl, const Texture& texture, const image::Image& picture, GLint minFilter, GLint wrap) {
  gl.BindTexture(GL_TEXTURE_2D, texture.get());
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, picture.width, picture.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, picture.rgba.data());
  gl.GenerateMipmap(GL_TEXTURE_2D);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
}

// A floor decal's square: [-1/2, 1/2] along x and z, scaled and turned per frame.
const std::vector<glm::vec3> kUnitFloorSquare = {{-0.5f, 0, -0.5f}, {0.5f, 0, 0.5f}, {0.5f, 0, -0.5f},
                                                 {-0.5f, 0, -0.5f}, {-0.5f, 0, 0.5f}, {0.5f, 0, 0.5f}};

void floatAttribute(const GlFunctions& gl, GLuint index, int components, std::size_t stride, std::size_t offset) {
  gl.EnableVertexAttribArray(index);
  gl.VertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                         reinterpret_cast<const void*>(offset));
}

}  // namespace

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

Renderer::Renderer(const RenderSettings& settings) : Renderer(settings, selectedGlBackend()) {}

Renderer::Renderer(const RenderSettings& settings, GlBackend backend) : settings_(settings) {
  validate(settings_);
  state_ = std::make_unique<GlState>(makeGlContext(backend));
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width, h = settings_.height;

  GLint maxSamples = 0;
  gl.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (settings_.antialiasing == Antialiasing::Msaa && settings_.msaa > maxSamples) {
    throw std::invalid_argument(fmt::format("render.msaa: this OpenGL allows at most {} samples, got {}", maxSamples, settings_.msaa));
  }
  const bool fxaa = settings_.antialiasing == Antialiasing::Fxaa;
  const bool multisampled = !fxaa && settings_.msaa > 1;
  state.drawTarget = makeFramebuffer(gl);
  state.drawDepthStencil = makeRenderbuffer(gl);
  gl.BindFramebuffer(GL_FRAMEBUFFER, state.drawTarget.get());
  if (fxaa) {
    state.fxaaProgram.emplace(gl, "fullscreen.vert", "fxaa.frag");
    state.sceneColour = makeTexture(gl);
    gl.BindTexture(GL_TEXTURE_2D, state.sceneColour.get());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, state.sceneColour.get(), 0);
  } else {
    state.drawColour = makeRenderbuffer(gl);
    gl.BindRenderbuffer(GL_RENDERBUFFER, state.drawColour.get());
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, multisampled ? settings_.msaa : 0, GL_RGBA8, w, h);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, state.drawColour.get());
  }
  gl.BindRenderbuffer(GL_RENDERBUFFER, state.drawDepthStencil.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, multisampled ? settings_.msaa : 0, GL_DEPTH24_STENCIL8, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, state.drawDepthStencil.get());
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(fmt::format("OpenGL: cannot create a {}x{} framebuffer with {} samples", w, h, settings_.msaa));
  }
  if (multisampled || fxaa) {
    state.resolveTarget = makeFramebuffer(gl);
    state.resolveColour = makeRenderbuffer(gl);
    gl.BindFramebuffer(GL_FRAMEBUFFER, state.resolveTarget.get());
    gl.BindRenderbuffer(GL_RENDERBUFFER, state.resolveColour.get());
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, state.resolveColour.get());
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error(fmt::format("OpenGL: cannot create a {}x{} resolve framebuffer", w, h));
    }
  }

  // The face pattern (assets/coin_face.png): row 0 of the image is body +Y, so the shader maps
  // t = (1 - Y / a) / 2 and the pixels go up unflipped. Mipmaps keep a distant coin from shimmering.
  uploadMipmapped(gl, state.coinFace, loadAssetImage("coin_face.png"), GL_LINEAR_MIPMAP_LINEAR, GL_CLAMP_TO_EDGE);

  // 512 texels per 10 cm: the 0.5 mm minor lines are 2.6 texels wide, so every mipmap level is
  // a faithful average of the one above. One mipmap level per lookup (not two blended) halves
  // the floor's texturing cost, the largest part of a frame on llvmpipe, with no visible seams.
  uploadMipmapped(gl, state.floorGrid, floorTile(512, palette(settings_.theme).floor), GL_LINEAR_MIPMAP_NEAREST, GL_REPEAT);

  // The overlay's glyphs at the size they are drawn: every texel row lands on one pixel row, so
  // the text is as sharp as the rasteriser made it, and no mipmaps are needed.
  const GlyphAtlas& atlas = state.atlas.emplace(overlayTextPixels(h));
  gl.BindTexture(GL_TEXTURE_2D, state.glyphs.get());
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, atlas.width(), atlas.height(), 0, GL_RED, GL_UNSIGNED_BYTE, atlas.coverage().data());
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  const std::vector<CoinVertex> coin = coinTriangles(settings_.coin, kCoinSegments);
  state.coinVertices = static_cast<GLsizei>(coin.size());
  gl.BindVertexArray(state.coinArray.get());
  upload(gl, state.coinBuffer.get(), coin, GL_STATIC_DRAW);
  floatAttribute(gl, 0, 3, sizeof(CoinVertex), offsetof(CoinVertex, position));
  floatAttribute(gl, 1, 3, sizeof(CoinVertex), offsetof(CoinVertex, normal));
  floatAttribute(gl, 2, 1, sizeof(CoinVertex), offsetof(CoinVertex, part));

  // The floor is one square around the camera target; the shader scales it (uniform "extent").
  // Counter-clockwise seen from above (+y), so back-face culling keeps it.
  const std::vector<glm::vec2> floorCorners = {{-1, -1}, {1, 1}, {1, -1}, {-1, -1}, {-1, 1}, {1, 1}};
  gl.BindVertexArray(state.floorArray.get());
  upload(gl, state.floorBuffer.get(), floorCorners, GL_STATIC_DRAW);
  floatAttribute(gl, 0, 2, sizeof(glm::vec2), 0);

  // The contact marker: a unit disc in the floor plane, scaled per frame.
  std::vector<glm::vec3> marker;
  for (int i = 0; i < 32; ++i) {
    const double a0 = 2 * std::numbers::pi * i / 32, a1 = 2 * std::numbers::pi * (i + 1) / 32;
    marker.insert(marker.end(), {glm::vec3(0), glm::vec3(std::cos(a1), 0, std::sin(a1)), glm::vec3(std::cos(a0), 0, std::sin(a0))});
  }
  state.markerVertices = static_cast<GLsizei>(marker.size());
  gl.BindVertexArray(state.markerArray.get());
  upload(gl, state.markerBuffer.get(), marker, GL_STATIC_DRAW);
  floatAttribute(gl, 0, 3, sizeof(glm::vec3), 0);

  gl.BindVertexArray(state.traceArray.get());
  gl.BindBuffer(GL_ARRAY_BUFFER, state.traceBuffer.get());
  floatAttribute(gl, 0, 2, sizeof(RibbonVertex), offsetof(RibbonVertex, position));
  floatAttribute(gl, 1, 1, sizeof(RibbonVertex), offsetof(RibbonVertex, age));
  floatAttribute(gl, 2, 1, sizeof(RibbonVertex), offsetof(RibbonVertex, sliding));

  gl.BindVertexArray(state.scaleBarArray.get());
  upload(gl, state.scaleBarBuffer.get(), kUnitFloorSquare, GL_STATIC_DRAW);
  floatAttribute(gl, 0, 3, sizeof(glm::vec3), 0);

  gl.BindVertexArray(state.hudArray.get());
  gl.BindBuffer(GL_ARRAY_BUFFER, state.hudBuffer.get());
  floatAttribute(gl, 0, 2, sizeof(TextVertex), offsetof(TextVertex, position));
  floatAttribute(gl, 1, 2, sizeof(TextVertex), offsetof(TextVertex, texel));
  floatAttribute(gl, 2, 4, sizeof(TextVertex), offsetof(TextVertex, colour));
  gl.BindVertexArray(0);
}

// Another Renderer's context may have been made current since this one last drew: its GL objects
// must be deleted in their own context, not in that one (where the same names may be in use).
Renderer::~Renderer() {
  if (state_) state_->context->makeCurrent();
}

GlBackend Renderer::backend() const { return state_->context->backend(); }

image::Image Renderer::draw(const FrameSnapshot& snapshot) {
  image::Image out;
  draw(snapshot, out);
  return out;
}

// Allocated on the first frame whose camera repeats, so orbit and follow clips never pay for it.
void Renderer::allocateBackgroundCache() {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width, h = settings_.height;
  const int samples = settings_.antialiasing == Antialiasing::Msaa && settings_.msaa > 1 ? settings_.msaa : 0;
  state.backgroundCache = makeFramebuffer(gl);
  state.backgroundColour = makeRenderbuffer(gl);
  state.backgroundDepthStencil = makeRenderbuffer(gl);
  gl.BindFramebuffer(GL_FRAMEBUFFER, state.backgroundCache.get());
  gl.BindRenderbuffer(GL_RENDERBUFFER, state.backgroundColour.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, state.backgroundColour.get());
  gl.BindRenderbuffer(GL_RENDERBUFFER, state.backgroundDepthStencil.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, state.backgroundDepthStencil.get());
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(fmt::format("OpenGL: cannot create a {}x{} background framebuffer", w, h));
  }
}

void Renderer::drawBackground(const CameraView& camera, const glm::mat4& viewProjection) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const float cameraDistance = glm::length(camera.eye - camera.target);
  const bool transparent = settings_.transparentBackground;
  const glm::vec3 background = palette(settings_.theme).backgroundSrgb;
  if (transparent) gl.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  else gl.ClearColor(background.r, background.g, background.b, 1.0f);
  gl.ClearStencil(0);
  gl.ClearDepth(1.0);
  gl.DepthMask(GL_TRUE);
  gl.StencilMask(0xFF);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);

  // Floor (writes depth so the coin's lower edge meets it correctly).
  state.floorProgram.use();
  state.floorProgram.set("viewProjection", viewProjection);
  state.floorProgram.set("centre", glm::vec2(camera.target.x, camera.target.z));
  state.floorProgram.set("extent", 150.0f * cameraDistance);
  state.floorProgram.set("eye", camera.eye);
  state.floorProgram.set("fogStart", 2.5f * cameraDistance);
  state.floorProgram.set("fogEnd", 12.0f * cameraDistance);
  state.floorProgram.set("backgroundSrgb", background);
  state.floorProgram.set("tileMetres", kFloorTileMetres);
  state.floorProgram.set("gridTile", 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, state.floorGrid.get());
  gl.BindVertexArray(state.floorArray.get());
  if (transparent) gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  gl.DrawArrays(GL_TRIANGLES, 0, 6);
  if (transparent) gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void Renderer::draw(const FrameSnapshot& snapshot, image::Image& out) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  state.context->makeCurrent();
  const int w = settings_.width, h = settings_.height;
  const CameraMatrices camera = cameraMatrices(snapshot.camera, w, h);
  const glm::mat4 viewProjection = camera.projection * camera.view;
  const float coinRadius = settings_.coin.radius;
  const Palette& colours = palette(settings_.theme);

  gl.BindFramebuffer(GL_FRAMEBUFFER, state.drawTarget.get());
  gl.Viewport(0, 0, w, h);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.Enable(GL_CULL_FACE);
  // Opaque: keep the destination alpha at 1 so the PNG is opaque whatever was blended over it.
  // Transparent: over a clear (0, 0, 0, 0) this blend leaves premultiplied colour and the coverage
  // in alpha, which MSAA resolves and FXAA average correctly; undone after the readback.
  if (settings_.transparentBackground) {
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  } else {
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  }
  gl.Disable(GL_BLEND);
  constexpr GLbitfield kAllBuffers = GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT;
  if (state.backgroundCamera == snapshot.camera) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.backgroundCache.get());
    gl.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, kAllBuffers, GL_NEAREST);
    gl.BindFramebuffer(GL_FRAMEBUFFER, state.drawTarget.get());
  } else {
    drawBackground(snapshot.camera, viewProjection);
    // Saved only once the camera has stayed put for a frame: a moving camera never pays the copy.
    if (settings_.reuseStaticBackground && state.previousCamera == snapshot.camera) {
      if (state.backgroundCache.get() == 0) allocateBackgroundCache();
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.drawTarget.get());
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, state.backgroundCache.get());
      gl.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, kAllBuffers, GL_NEAREST);
      gl.BindFramebuffer(GL_FRAMEBUFFER, state.drawTarget.get());
      state.backgroundCamera = snapshot.camera;
    }
  }
  state.previousCamera = snapshot.camera;

  // Decals on the floor: nothing but the coins can hide them, and those are drawn afterwards.
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.Enable(GL_BLEND);
  if (settings_.showShadow) {
    // The stencil lets each floor pixel be darkened once, however many shadow triangles overlap.
    gl.Enable(GL_STENCIL_TEST);
    gl.StencilFunc(GL_EQUAL, 0, 0xFF);
    gl.StencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    state.flatProgram.use();
    state.flatProgram.set("viewProjection", viewProjection);
    state.flatProgram.set("colour", kShadowColour);
    gl.BindVertexArray(state.coinArray.get());
    const glm::mat4 shadow = floorShadowProjection(0.0f);
    state.flatProgram.set("model", shadow * modelMatrix(snapshot.coin));
    gl.DrawArrays(GL_TRIANGLES, 0, state.coinVertices);
    state.flatProgram.set("colour", glm::vec4(glm::vec3(kShadowColour), 0.5f * kShadowColour.a));
    for (const CoinPose& ghost : snapshot.ghosts) {
      state.flatProgram.set("model", shadow * modelMatrix(ghost));
      gl.DrawArrays(GL_TRIANGLES, 0, state.coinVertices);
    }
    gl.Disable(GL_STENCIL_TEST);
  }
  if (const std::vector<RibbonVertex> ribbon = ribbonStrip(snapshot.trace, snapshot.traceWidth, snapshot.traceSlides);
      !ribbon.empty()) {
    state.traceProgram.use();
    state.traceProgram.set("viewProjection", viewProjection);
    state.traceProgram.set("recentRolling", colours.trace.recentRolling);
    state.traceProgram.set("oldRolling", colours.trace.oldRolling);
    state.traceProgram.set("recentSliding", colours.trace.recentSliding);
    state.traceProgram.set("oldSliding", colours.trace.oldSliding);
    state.traceProgram.set("opacity", colours.trace.opacity);
    gl.BindVertexArray(state.traceArray.get());
    upload(gl, state.traceBuffer.get(), ribbon, GL_STREAM_DRAW);
    gl.DrawArrays(GL_TRIANGLE_STRIP, 0, static_cast<GLsizei>(ribbon.size()));
  }
  if (snapshot.showContact && !snapshot.trace.empty()) {
    state.flatProgram.use();
    state.flatProgram.set("viewProjection", viewProjection);
    state.flatProgram.set("colour", kContactColour);
    const glm::vec2 contact = snapshot.trace.back();
    const float markerRadius = std::max(0.08f * coinRadius, 1.6f * snapshot.traceWidth);
    state.flatProgram.set("model", glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(contact.x, 0.0f, contact.y)),
                                              glm::vec3(markerRadius)));
    gl.BindVertexArray(state.markerArray.get());
    gl.DrawArrays(GL_TRIANGLES, 0, state.markerVertices);
  }
  std::optional<ScaleBarPlacement> scaleBar;
  if (settings_.scaleBar.shown) {
    const ScaleBarPlacement& bar = scaleBar.emplace(placeScaleBar(settings_.scaleBar, coinRadius, snapshot.camera, snapshot.coin, h));
    const glm::vec3 along = bar.end - bar.start;
    glm::mat4 model(1.0f);
    model[0] = glm::vec4(along, 0.0f);
    model[2] = glm::vec4(bar.thickness * bar.across, 0.0f);
    model[3] = glm::vec4(0.5f * (bar.start + bar.end), 1.0f);
    state.flatProgram.use();
    state.flatProgram.set("viewProjection", viewProjection);
    state.flatProgram.set("colour", colours.scaleBar);
    state.flatProgram.set("model", model);
    gl.BindVertexArray(state.scaleBarArray.get());
    gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(kUnitFloorSquare.size()));
  }

  // Coins: the current one opaque, then the ghosts from far to near so nearer ones blend last.
  gl.Enable(GL_DEPTH_TEST);
  gl.Enable(GL_CULL_FACE);
  state.coinProgram.use();
  state.coinProgram.set("viewProjection", viewProjection);
  state.coinProgram.set("eye", snapshot.camera.eye);
  state.coinProgram.set("lightDirection", kLightDirection);
  // The face pattern spans the flat part of each face, inside the fillets (radius - rho); with a
  // sharp rim that is the whole radius, exactly as before fillets existed.
  state.coinProgram.set("radius", coinRadius - settings_.coin.edgeRadius);
  state.coinProgram.set("face", 0);
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, state.coinFace.get());
  gl.BindVertexArray(state.coinArray.get());
  auto drawCoin = [&](const CoinPose& pose, float opacity, glm::vec4 tint) {
    const glm::mat4 model = modelMatrix(pose);
    state.coinProgram.set("model", model);
    state.coinProgram.set("normalMatrix", glm::mat3_cast(pose.attitude));
    state.coinProgram.set("opacity", opacity);
    state.coinProgram.set("tint", tint);
    gl.DrawArrays(GL_TRIANGLES, 0, state.coinVertices);
  };
  gl.Disable(GL_BLEND);
  drawCoin(snapshot.coin, 1.0f, glm::vec4(0.0f));
  if (!snapshot.ghosts.empty()) {
    std::vector<const CoinPose*> farToNear;
    for (const CoinPose& ghost : snapshot.ghosts) farToNear.push_back(&ghost);
    std::stable_sort(farToNear.begin(), farToNear.end(), [&](const CoinPose* a, const CoinPose* b) {
      return glm::length(a->centre - snapshot.camera.eye) > glm::length(b->centre - snapshot.camera.eye);
    });
    gl.Enable(GL_BLEND);
    for (const CoinPose* ghost : farToNear) {
      const auto age = static_cast<std::size_t>(ghost - snapshot.ghosts.data());
      drawCoin(*ghost, 0.5f, glm::vec4(ghostColour(age, snapshot.ghosts.size()), 0.85f));
    }
  }

  // The overlay goes on after anti-aliasing: FXAA would soften the text, MSAA gains nothing on it.
  const bool fxaa = settings_.antialiasing == Antialiasing::Fxaa;
  if (fxaa) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, state.resolveTarget.get());
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);
    state.fxaaProgram->use();
    state.fxaaProgram->set("scene", 0);
    state.fxaaProgram->set("texelSize", glm::vec2(1.0f / static_cast<float>(w), 1.0f / static_cast<float>(h)));
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, state.sceneColour.get());
    gl.BindVertexArray(state.fullScreenArray.get());
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  std::vector<TextVertex> text;
  const GlyphAtlas& atlas = *state.atlas;
  if (!snapshot.hudLines.empty()) {
    const float margin = std::round(0.5f * atlas.lineHeight());
    appendTextPanel(atlas, snapshot.hudLines, glm::vec2(margin), colours.overlay, text);
  }
  if (scaleBar) {  // the label centred under the bar's middle
    const glm::vec2 middle = pixelFromWorld(snapshot.camera, w, h, 0.5f * (scaleBar->start + scaleBar->end));
    const glm::vec2 size = textPanelSize(atlas, {scaleBar->label});
    appendTextPanel(atlas, {scaleBar->label}, middle + glm::vec2(-0.5f * size.x, 0.4f * atlas.lineHeight()), colours.overlay, text);
  }
  if (!text.empty()) {
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Enable(GL_BLEND);
    state.hudProgram.use();
    state.hudProgram.set("viewportSize", glm::vec2(w, h));
    state.hudProgram.set("atlasSize", glm::vec2(atlas.width(), atlas.height()));
    state.hudProgram.set("atlas", 0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, state.glyphs.get());
    gl.BindVertexArray(state.hudArray.get());
    upload(gl, state.hudBuffer.get(), text, GL_STREAM_DRAW);
    gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(text.size()));
  }
  gl.BindVertexArray(0);

  if (fxaa) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.resolveTarget.get());
  } else if (settings_.msaa > 1) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.drawTarget.get());
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, state.resolveTarget.get());
    gl.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, kAllBuffers, GL_NEAREST);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.resolveTarget.get());
  } else {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.drawTarget.get());
  }
  if (out.width != w || out.height != h) out = image::Image(w, h);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
  // OpenGL's rows run bottom-up; Image's run top-down.
  const std::size_t rowBytes = static_cast<std::size_t>(w) * 4;
  std::vector<std::uint8_t> row(rowBytes);
  for (int y = 0; y < h / 2; ++y) {
    std::uint8_t* top = out.rgba.data() + static_cast<std::size_t>(y) * rowBytes;
    std::uint8_t* bottom = out.rgba.data() + static_cast<std::size_t>(h - 1 - y) * rowBytes;
    std::memcpy(row.data(), top, rowBytes);
    std::memcpy(top, bottom, rowBytes);
    std::memcpy(bottom, row.data(), rowBytes);
  }
  // Images, PNG and the video encoders hold straight (not premultiplied) alpha.
  if (settings_.transparentBackground) {
    for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
      const unsigned alpha = out.rgba[i + 3];
      if (alpha == 0 || alpha == 255) continue;
      for (std::size_t c = 0; c < 3; ++c) {
        out.rgba[i + c] = static_cast<std::uint8_t>(std::min(255u, (out.rgba[i + c] * 255u + alpha / 2) / alpha));
      }
    }
  }
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) {
    throw std::runtime_error(fmt::format("OpenGL error 0x{:04x} while drawing a frame", error));
  }
}

}  // namespace coinroll::render
