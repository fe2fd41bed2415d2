// Renderer's per-frame work: draw() and the passes it runs, in order, on the GL objects the
// constructor (renderer.cpp) made.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <stdexcept>
#include <vector>

#include "render/camera.h"
#include "render/floor_tile.h"
#include "render/inset_plot.h"
#include "render/overlay_text.h"
#include "render/renderer.h"
#include "render/renderer_state.h"
#include "render/scale_bar.h"
#include "render/theme.h"

namespace coinroll::render {

namespace {

const glm::vec4 kShadowColour(0.0f, 0.0f, 0.0f, 0.45f);
const glm::vec4 kContactColour(0.85f, 0.1f, 0.08f, 1.0f);
constexpr GLbitfield kAllBuffers = GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT;

// A strobe copy's tint, linear: dark blue (oldest) through grey to yellow (newest), cividis' ends,
// rising in lightness so the copies read in order where they overlap, in grey print and for
// colour-blind readers.
glm::vec3 ghostColour(std::size_t age, std::size_t count) {
  const glm::vec3 oldest(0.0f, 0.05f, 0.45f), middle(0.22f, 0.22f, 0.24f), newest(0.95f, 0.80f, 0.02f);
  const float f = count > 1 ? static_cast<float>(age) / static_cast<float>(count - 1) : 1.0f;
  return f < 0.5f ? glm::mix(oldest, middle, 2.0f * f) : glm::mix(middle, newest, 2.0f * f - 1.0f);
}

glm::mat4 modelMatrix(const CoinPose& pose) {
  return glm::translate(glm::mat4(1.0f), pose.centre) * glm::mat4_cast(pose.attitude);
}

// Projects points onto the floor (y = lift) along the light direction: a planar shadow, exact for
// a flat receiver and far cheaper than a shadow map on a software rasteriser.
glm::mat4 floorShadowProjection(float lift) {
  const glm::vec3 l = kLightDirection;
  glm::mat4 m(1.0f);
  m[1] = glm::vec4(-l.x / l.y, 0.0f, -l.z / l.y, 0.0f);  // column y: x' = x - (l.x/l.y)(y - lift), ...
  m[3] = glm::vec4(l.x / l.y * lift, lift, l.z / l.y * lift, 1.0f);
  return m;
}

}  // namespace

image::Image Renderer::draw(const FrameSnapshot& snapshot) {
  image::Image out;
  draw(snapshot, out);
  return out;
}

void Renderer::draw(const FrameSnapshot& snapshot, image::Image& out) {
  state_->context->makeCurrent();
  const CameraMatrices camera = cameraMatrices(snapshot.camera, settings_.width, settings_.height);
  const glm::mat4 viewProjection = camera.projection * camera.view;

  bindDrawTarget();
  drawOrRestoreBackground(snapshot.camera, viewProjection);
  const std::optional<ScaleBarPlacement> scaleBar = drawFloorDecals(snapshot, viewProjection);
  drawCoins(snapshot, viewProjection);
  // The overlay goes on after anti-aliasing: FXAA would soften the text, MSAA gains nothing on it,
  // and supersampled it would be glyphs twice the size shrunk, not the atlas's.
  if (settings_.antialiasing == Antialiasing::Fxaa) applyFxaa();
  if (settings_.antialiasing == Antialiasing::Ssaa) downsampleSupersampled();
  drawOverlay(snapshot, scaleBar);
  readBack(out);
  if (const GLenum error = state_->gl.GetError(); error != GL_NO_ERROR) {
    throw std::runtime_error(fmt::format("OpenGL error 0x{:04x} while drawing a frame", error));
  }
}

void Renderer::bindDrawTarget() {
  const GlFunctions& gl = state_->gl;
  gl.BindFramebuffer(GL_FRAMEBUFFER, state_->drawTarget.get());
  gl.Viewport(0, 0, settings_.width * drawScale(settings_), settings_.height * drawScale(settings_));
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
}

void Renderer::drawOrRestoreBackground(const CameraView& camera, const glm::mat4& viewProjection) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width * drawScale(settings_), h = settings_.height * drawScale(settings_);
  if (state.backgroundCamera == camera) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.backgroundCache.get());
    gl.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, kAllBuffers, GL_NEAREST);
    gl.BindFramebuffer(GL_FRAMEBUFFER, state.drawTarget.get());
  } else {
    drawBackground(camera, viewProjection);
    // Saved only once the camera has stayed put for a frame: a moving camera never pays the copy.
    if (settings_.reuseStaticBackground && state.previousCamera == camera) {
      if (state.backgroundCache.get() == 0) allocateBackgroundCache();
      gl.BindFramebuffer(GL_READ_FRAMEBUFFER, state.drawTarget.get());
      gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, state.backgroundCache.get());
      gl.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, kAllBuffers, GL_NEAREST);
      gl.BindFramebuffer(GL_FRAMEBUFFER, state.drawTarget.get());
      state.backgroundCamera = camera;
    }
  }
  state.previousCamera = camera;
}

// Allocated on the first frame whose camera repeats, so orbit and follow clips never pay for it.
void Renderer::allocateBackgroundCache() {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width * drawScale(settings_), h = settings_.height * drawScale(settings_);
  const int samples = isMultisampled(settings_) ? settings_.msaa : 0;
  state.backgroundCache = makeFramebuffer(gl);
  state.backgroundColour = makeRenderbuffer(gl);
  state.backgroundDepthStencil = makeRenderbuffer(gl);
  gl.BindFramebuffer(GL_FRAMEBUFFER, state.backgroundCache.get());
  gl.BindRenderbuffer(GL_RENDERBUFFER, state.backgroundColour.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, state.backgroundColour.get());
  gl.BindRenderbuffer(GL_RENDERBUFFER, state.backgroundDepthStencil.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, w, h);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                             state.backgroundDepthStencil.get());
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
  if (transparent)
    gl.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  else
    gl.ClearColor(background.r, background.g, background.b, 1.0f);
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

// Decals on the floor: nothing but the coins can hide them, and those are drawn afterwards.
std::optional<ScaleBarPlacement> Renderer::drawFloorDecals(const FrameSnapshot& snapshot,
                                                           const glm::mat4& viewProjection) {
  const GlFunctions& gl = state_->gl;
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.Enable(GL_BLEND);
  if (settings_.showShadow) drawShadows(snapshot, viewProjection);
  drawTrace(snapshot, viewProjection);
  const bool inTheAir = !snapshot.traceFlies.empty() && snapshot.traceFlies.back();
  if (snapshot.showContact && !snapshot.trace.empty() && !inTheAir) drawContactMarker(snapshot, viewProjection);
  if (!settings_.scaleBar.shown) return std::nullopt;
  return drawScaleBar(snapshot, viewProjection);
}

void Renderer::drawShadows(const FrameSnapshot& snapshot, const glm::mat4& viewProjection) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
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

void Renderer::drawTrace(const FrameSnapshot& snapshot, const glm::mat4& viewProjection) {
  const std::vector<RibbonVertex> ribbon =
      ribbonStrip(snapshot.trace, snapshot.traceWidth, snapshot.traceSlides, snapshot.traceFlies);
  if (ribbon.empty()) return;
  GlState& state = *state_;
  const TraceColours& colours = palette(settings_.theme).trace;
  state.traceProgram.use();
  state.traceProgram.set("viewProjection", viewProjection);
  state.traceProgram.set("recentRolling", colours.recentRolling);
  state.traceProgram.set("oldRolling", colours.oldRolling);
  state.traceProgram.set("recentSliding", colours.recentSliding);
  state.traceProgram.set("oldSliding", colours.oldSliding);
  state.traceProgram.set("opacity", colours.opacity);
  state.gl.BindVertexArray(state.traceArray.get());
  upload(state.gl, state.traceBuffer.get(), ribbon, GL_STREAM_DRAW);
  state.gl.DrawArrays(GL_TRIANGLE_STRIP, 0, static_cast<GLsizei>(ribbon.size()));
}

void Renderer::drawContactMarker(const FrameSnapshot& snapshot, const glm::mat4& viewProjection) {
  GlState& state = *state_;
  state.flatProgram.use();
  state.flatProgram.set("viewProjection", viewProjection);
  state.flatProgram.set("colour", kContactColour);
  const glm::vec2 contact = snapshot.trace.back();
  const float markerRadius = std::max(0.08f * settings_.coin.radius, 1.6f * snapshot.traceWidth);
  state.flatProgram.set("model", glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(contact.x, 0.0f, contact.y)),
                                            glm::vec3(markerRadius)));
  state.gl.BindVertexArray(state.markerArray.get());
  state.gl.DrawArrays(GL_TRIANGLES, 0, state.markerVertices);
}

ScaleBarPlacement Renderer::drawScaleBar(const FrameSnapshot& snapshot, const glm::mat4& viewProjection) {
  GlState& state = *state_;
  ScaleBarPlacement bar =
      placeScaleBar(settings_.scaleBar, settings_.coin.radius, snapshot.camera, snapshot.coin, settings_.height);
  const glm::vec3 along = bar.end - bar.start;
  glm::mat4 model(1.0f);
  model[0] = glm::vec4(along, 0.0f);
  model[2] = glm::vec4(bar.thickness * bar.across, 0.0f);
  model[3] = glm::vec4(0.5f * (bar.start + bar.end), 1.0f);
  state.flatProgram.use();
  state.flatProgram.set("viewProjection", viewProjection);
  state.flatProgram.set("colour", palette(settings_.theme).scaleBar);
  state.flatProgram.set("model", model);
  state.gl.BindVertexArray(state.scaleBarArray.get());
  state.gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(kUnitFloorSquare.size()));
  return bar;
}

// The current coin opaque, then the ghosts from far to near so nearer ones blend last. The ghosts
// test depth against the opaque scene but write none: copies that nearly coincide (a coin spinning
// in place) would otherwise hide each other ridge by ridge of the knurled rim, in saw teeth, where
// they should blend; back faces are culled, so each copy still shows only its near side.
void Renderer::drawCoins(const FrameSnapshot& snapshot, const glm::mat4& viewProjection) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  gl.Enable(GL_DEPTH_TEST);
  gl.Enable(GL_CULL_FACE);
  state.coinProgram.use();
  state.coinProgram.set("viewProjection", viewProjection);
  state.coinProgram.set("eye", snapshot.camera.eye);
  state.coinProgram.set("lightDirection", kLightDirection);
  // The face pattern spans the flat part of each face, inside the fillets (radius - rho); with a
  // sharp rim that is the whole radius, exactly as before fillets existed.
  state.coinProgram.set("radius", settings_.coin.radius - settings_.coin.edgeRadius);
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
  if (snapshot.ghosts.empty()) return;
  std::vector<const CoinPose*> farToNear;
  for (const CoinPose& ghost : snapshot.ghosts) farToNear.push_back(&ghost);
  std::stable_sort(farToNear.begin(), farToNear.end(), [&](const CoinPose* a, const CoinPose* b) {
    return glm::length(a->centre - snapshot.camera.eye) > glm::length(b->centre - snapshot.camera.eye);
  });
  gl.Enable(GL_BLEND);
  gl.DepthMask(GL_FALSE);
  for (const CoinPose* ghost : farToNear) {
    const auto age = static_cast<std::size_t>(ghost - snapshot.ghosts.data());
    drawCoin(*ghost, 0.5f, glm::vec4(ghostColour(age, snapshot.ghosts.size()), 0.85f));
  }
  gl.DepthMask(GL_TRUE);
}

// Filters the scene texture into the resolve target, which the overlay and the readback then use.
void Renderer::applyFxaa() {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  gl.BindFramebuffer(GL_FRAMEBUFFER, state.resolveTarget.get());
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.Disable(GL_BLEND);
  state.fxaaProgram->use();
  state.fxaaProgram->set("scene", 0);
  state.fxaaProgram->set(
      "texelSize", glm::vec2(1.0f / static_cast<float>(settings_.width), 1.0f / static_cast<float>(settings_.height)));
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, state.sceneColour.get());
  gl.BindVertexArray(state.fullScreenArray.get());
  gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

// Averages each drawn kSupersampleFactor x kSupersampleFactor block into the resolve target, which
// the overlay (drawn at the picture's own size, so its glyphs stay the atlas's) and the readback use.
void Renderer::downsampleSupersampled() {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width, h = settings_.height;
  const int drawWidth = w * kSupersampleFactor, drawHeight = h * kSupersampleFactor;
  GLuint drawn = state.drawTarget.get();
  if (isMultisampled(settings_)) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, drawn);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, state.supersampleTarget.get());
    gl.BlitFramebuffer(0, 0, drawWidth, drawHeight, 0, 0, drawWidth, drawHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    drawn = state.supersampleTarget.get();
  }
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, drawn);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, state.resolveTarget.get());
  gl.BlitFramebuffer(0, 0, drawWidth, drawHeight, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  gl.BindFramebuffer(GL_FRAMEBUFFER, state.resolveTarget.get());
  gl.Viewport(0, 0, w, h);
}

void Renderer::drawOverlay(const FrameSnapshot& snapshot, const std::optional<ScaleBarPlacement>& scaleBar) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width, h = settings_.height;
  const Palette& colours = palette(settings_.theme);
  std::vector<TextVertex> text;
  const GlyphAtlas& atlas = *state.atlas;
  if (!snapshot.hudLines.empty()) {
    const float margin = std::round(0.5f * atlas.lineHeight());
    appendTextPanel(atlas, snapshot.hudLines, glm::vec2(margin), colours.overlay, text);
  }
  if (scaleBar) {  // the label centred under the bar's middle
    const glm::vec2 middle = pixelFromWorld(snapshot.camera, w, h, 0.5f * (scaleBar->start + scaleBar->end));
    const glm::vec2 size = textPanelSize(atlas, {scaleBar->label});
    appendTextPanel(atlas, {scaleBar->label}, middle + glm::vec2(-0.5f * size.x, 0.4f * atlas.lineHeight()),
                    colours.overlay, text);
  }
  if (snapshot.inset) appendInsetPlot(atlas, *snapshot.inset, w, h, colours.overlay, text);
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
}

// Resolves the multisampled picture if there is one, then reads it into `out` top row first,
// with straight alpha.
void Renderer::readBack(image::Image& out) {
  GlState& state = *state_;
  const GlFunctions& gl = state.gl;
  const int w = settings_.width, h = settings_.height;
  if (settings_.antialiasing == Antialiasing::Fxaa || settings_.antialiasing == Antialiasing::Ssaa) {
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
}

}  // namespace coinroll::render
