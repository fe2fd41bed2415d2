#include "render/renderer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "render/assets.h"
#include "render/floor_tile.h"
#include "render/overlay_text.h"
#include "render/renderer_state.h"
#include "render/theme.h"

namespace coinroll::render {

namespace {

void validate(const RenderSettings& s) {
  for (const auto& [field, side] : {std::pair{"width", s.width}, std::pair{"height", s.height}}) {
    if (side < kMinImageSide || side > kMaxImageSide) {
      throw std::invalid_argument(
          fmt::format("render.{}: must be {}..{} pixels, got {}", field, kMinImageSide, kMaxImageSide, side));
    }
  }
  if (s.antialiasing == Antialiasing::Auto) {
    throw std::invalid_argument(
        "render.antialiasing: auto names a choice per output, made before drawing "
        "(scene::RenderSpec::pictureFor), not a method a Renderer can draw with");
  }
  if (!isMsaaSampleCount(s.msaa) && s.antialiasing != Antialiasing::Fxaa) {
    throw std::invalid_argument(
        fmt::format("render.msaa: must be one of {} samples, got {}", fmt::join(kMsaaSampleCounts, ", "), s.msaa));
  }
  if (!(s.coin.radius > 0) || !(s.coin.thickness > 0) ||
      !(s.coin.innerRadius >= 0 && s.coin.innerRadius < s.coin.radius)) {
    throw std::invalid_argument(fmt::format("coin: radius {} m, inner radius {} m and thickness {} m cannot be drawn",
                                            s.coin.radius, s.coin.innerRadius, s.coin.thickness));
  }
  // The fillet must fit the cross-section: at most half the thickness (a half-torus rim) and at
  // most the rim's width (the flat face then shrinks to the hole's edge or the centre).
  const float maxEdgeRadius = std::min(0.5f * s.coin.thickness, s.coin.radius - s.coin.innerRadius);
  if (!(s.coin.edgeRadius >= 0 && s.coin.edgeRadius <= maxEdgeRadius)) {
    throw std::invalid_argument(
        fmt::format("coin: edge radius {} m cannot be drawn: must be 0..{} m (at most half the "
                    "thickness {} m and the width radius - inner radius {} m)",
                    s.coin.edgeRadius, maxEdgeRadius, s.coin.thickness, s.coin.radius - s.coin.innerRadius));
  }
}

void uploadMipmapped(const GlFunctions& gl, const Texture& texture, const image::Image& picture, GLint minFilter,
                     GLint wrap) {
  gl.BindTexture(GL_TEXTURE_2D, texture.get());
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, picture.width, picture.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                picture.rgba.data());
  gl.GenerateMipmap(GL_TEXTURE_2D);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
}

void floatAttribute(const GlFunctions& gl, GLuint index, int components, std::size_t stride, std::size_t offset) {
  gl.EnableVertexAttribArray(index);
  gl.VertexAttribPointer(index, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride),
                         reinterpret_cast<const void*>(offset));
}

}  // namespace

Renderer::Renderer(const RenderSettings& settings) : Renderer(settings, selectedGlBackend()) {}

Renderer::Renderer(const RenderSettings& settings, GlBackend backend) : settings_(settings) {
  validate(settings_);
  state_ = std::make_unique<GlState>(makeGlContext(backend));
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width, h = settings_.height;

  GLint maxSamples = 0, maxRenderbufferSide = 0;
  gl.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbufferSide);
  if (settings_.antialiasing != Antialiasing::Fxaa && settings_.msaa > maxSamples) {
    throw std::invalid_argument(
        fmt::format("render.msaa: this OpenGL allows at most {} samples, got {}", maxSamples, settings_.msaa));
  }
  const bool fxaa = settings_.antialiasing == Antialiasing::Fxaa;
  const bool supersampled = settings_.antialiasing == Antialiasing::Ssaa;
  const bool multisampled = isMultisampled(settings_);
  const int samples = multisampled ? settings_.msaa : 0;
  const int drawWidth = w * drawScale(settings_), drawHeight = h * drawScale(settings_);
  if (std::max(drawWidth, drawHeight) > maxRenderbufferSide) {
    throw std::invalid_argument(
        fmt::format("render.antialiasing: ssaa draws {}x{} pixels, and this OpenGL allows at "
                    "most {} a side; use msaa for a {}x{} picture",
                    drawWidth, drawHeight, maxRenderbufferSide, w, h));
  }
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
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, drawWidth, drawHeight);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, state.drawColour.get());
  }
  gl.BindRenderbuffer(GL_RENDERBUFFER, state.drawDepthStencil.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, drawWidth, drawHeight);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                             state.drawDepthStencil.get());
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error(fmt::format("OpenGL: cannot create a {}x{} framebuffer with {} samples", drawWidth,
                                         drawHeight, settings_.msaa));
  }
  const auto makeColourTarget = [&](Framebuffer& target, Renderbuffer& colour, int width, int height) {
    target = makeFramebuffer(gl);
    colour = makeRenderbuffer(gl);
    gl.BindFramebuffer(GL_FRAMEBUFFER, target.get());
    gl.BindRenderbuffer(GL_RENDERBUFFER, colour.get());
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.get());
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error(fmt::format("OpenGL: cannot create a {}x{} resolve framebuffer", width, height));
    }
  };
  if (multisampled || fxaa || supersampled) makeColourTarget(state.resolveTarget, state.resolveColour, w, h);
  // A blit cannot resolve samples and scale at once: the samples are resolved at the drawn size first.
  if (supersampled && multisampled) {
    makeColourTarget(state.supersampleTarget, state.supersampleColour, drawWidth, drawHeight);
  }

  // The face pattern (assets/coin_face.png): row 0 of the image is body +Y, so the shader maps
  // t = (1 - Y / a) / 2 and the pixels go up unflipped. Mipmaps keep a distant coin from shimmering.
  uploadMipmapped(gl, state.coinFace, loadAssetImage("coin_face.png"), GL_LINEAR_MIPMAP_LINEAR, GL_CLAMP_TO_EDGE);

  // 512 texels per 10 cm: the 0.5 mm minor lines are 2.6 texels wide, so every mipmap level is
  // a faithful average of the one above. Two levels blended per lookup: with one, the floor shows
  // a seam where the level changes (sharp lines beside blurred ones), plain on the paper theme's
  // dark lines on white. The floor is drawn once per camera position (a fixed camera reuses it).
  uploadMipmapped(gl, state.floorGrid, floorTile(512, palette(settings_.theme).floor), GL_LINEAR_MIPMAP_LINEAR,
                  GL_REPEAT);

  // The overlay's glyphs at the size they are drawn: every texel row lands on one pixel row, so
  // the text is as sharp as the rasteriser made it, and no mipmaps are needed.
  const GlyphAtlas& atlas = state.atlas.emplace(overlayTextPixels(h));
  gl.BindTexture(GL_TEXTURE_2D, state.glyphs.get());
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, atlas.width(), atlas.height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                atlas.coverage().data());
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
    marker.insert(marker.end(),
                  {glm::vec3(0), glm::vec3(std::cos(a1), 0, std::sin(a1)), glm::vec3(std::cos(a0), 0, std::sin(a0))});
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

}  // namespace coinroll::render
