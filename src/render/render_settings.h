#pragma once
// What a Renderer is built with: picture size, anti-aliasing, the coin's drawn shape. Plain data,
// std and image/picture_size.h only, so src/scene can hold these settings (and validate a scene
// file into them) without seeing OpenGL: the one definition of each default and limit.

#include <algorithm>
#include <array>

#include "image/picture_size.h"

namespace coinroll::render {

// Picture sides, pixels. The lower bound keeps the overlay and the grid legible; the upper is 8K
// UHD's width: one 7680 x 4320 picture with 4x MSAA already takes about 1 GiB of colour and
// depth-stencil samples in llvmpipe, so a larger number is a typo rather than a wish.
inline constexpr int kMinImageSide = 16;
inline constexpr int kMaxImageSide = 7680;

// Degrees: the vertical field of view of a camera not told otherwise, render.camera.fov's default
// and a CameraView's, defined once for both.
inline constexpr float kDefaultFovYDegrees = 35.0f;

// The MSAA sample counts a scene may ask for; the Renderer also refuses more than its OpenGL's
// GL_MAX_SAMPLES (llvmpipe's is 4 on Debian 12).
inline constexpr std::array<int, 4> kMsaaSampleCounts = {1, 2, 4, 8};

inline constexpr bool isMsaaSampleCount(int samples) {
  return std::find(kMsaaSampleCounts.begin(), kMsaaSampleCounts.end(), samples) != kMsaaSampleCounts.end();
}

// Msaa: `msaa` samples per pixel, resolved by a blit. Fxaa: one sample per pixel and a fast
// approximate anti-aliasing pass over the picture (shaders/fxaa.frag); `msaa` is ignored.
// Ssaa: drawn at kSupersampleFactor times the width and height with `msaa` samples per pixel there,
// each kSupersampleFactor x kSupersampleFactor block then averaged into one pixel: unlike MSAA, the
// floor's texture and the shading are sampled that many times too (docs/quality.md "Anti-aliasing").
// Auto: the scene's default, which the pipeline turns into one of the others for each output
// (scene::RenderSpec::pictureFor); a Renderer refuses it.
enum class Antialiasing { Msaa, Fxaa, Ssaa, Auto };

// Ssaa's factor per side. 2: a 2:1 linear blit lands every output pixel's centre between four
// drawn pixels, so the blit is the exact 2x2 box average; 16x the pixels (4 per side) cost 4x more.
inline constexpr int kSupersampleFactor = 2;

// The coin as drawn: a closed cylinder, an annulus when it has a hole, whose two outer edges may
// be rounded. In the (r, z) half-plane its cross-section is [innerRadius, radius] x [-h/2, h/2]
// with the outer corners replaced by quarter circles of radius edgeRadius centred at
// (radius - edgeRadius, +-(h/2 - edgeRadius)): the physics' torus rim (physics/rim.h).
struct CoinShape {
  float radius = 0.0375f;      // m
  float innerRadius = 0.0f;    // m, 0 for a solid disk
  float thickness = 0.00225f;  // m
  float edgeRadius = 0.0f;     // m, rho: the fillet rounding the outer rim, in [0, min(thickness/2, radius -
                               // innerRadius)]; 0 a sharp-edged cylinder, thickness/2 a fully rounded (half-torus) rim
};

// render.theme. Classic: a dark floor under a pale sky, light text on dark panels. Paper: for print,
// a near-white floor and background with dark grid lines, dark text on light panels, and a trace
// in dark red to dark blue (dark orange to green where it slid) that survives a grey printer.
enum class Theme { Classic, Paper };

// render.scale_bar: a bar of a round length lying on the floor just in front of the coin, across
// the view, with its length written under it ("2 cm"); it is drawn in perspective, so it measures
// the floor where it lies (docs/outputs.md "Scale bar").
struct ScaleBar {
  bool shown = false;
  float metres = 0.0f;  // m, > 0; 0 with `shown`: the largest 1, 2 or 5 x 10^k m not above the coin's radius
};

struct RenderSettings {
  int width = image::kDefaultPictureWidth,
      height = image::kDefaultPictureHeight;  // pixels, in [kMinImageSide, kMaxImageSide]
  Antialiasing antialiasing = Antialiasing::Msaa;
  int msaa = 4;  // samples per pixel, one of kMsaaSampleCounts (1: none)
  CoinShape coin;
  bool showShadow = true;
  // render.background "transparent": no sky and no visible floor (it still hides what lies below
  // it); where nothing is drawn alpha is 0, and the coin, its shadow, the trace and the overlay
  // keep their own alpha (docs/outputs.md "Transparent background").
  bool transparentBackground = false;
  Theme theme = Theme::Classic;
  ScaleBar scaleBar = {};
  // When a frame's camera equals the previous frame's, the sky and the floor are copied from the
  // first such frame instead of shaded again (the largest part of a frame on llvmpipe). The bytes
  // are the same either way; off only to measure or test the saving.
  bool reuseStaticBackground = true;
};

// The pixels drawn per picture pixel along each side: kSupersampleFactor for Ssaa, else 1.
inline constexpr int drawScale(const RenderSettings& settings) {
  return settings.antialiasing == Antialiasing::Ssaa ? kSupersampleFactor : 1;
}

// Whether the drawing buffers hold `msaa` samples per pixel (Msaa and Ssaa with msaa > 1).
inline constexpr bool isMultisampled(const RenderSettings& settings) {
  return (settings.antialiasing == Antialiasing::Msaa || settings.antialiasing == Antialiasing::Ssaa) &&
         settings.msaa > 1;
}

}  // namespace coinroll::render
