#pragma once
// Where render.scale_bar lies (render_settings.h ScaleBar), computed without a GL context so a test
// can project it with a camera of its own: on the floor, centred a coin's diameter in front of the
// coin (towards the camera), across the view, so both ends stand at one depth and the bar is
// horizontal in the picture at the floor's scale where it lies.

#include <glm/glm.hpp>
#include <string>

#include "render/frame_snapshot.h"
#include "render/render_settings.h"

namespace coinroll::render {

struct ScaleBarPlacement {
  glm::vec3 start{0.0f}, end{0.0f};  // m, on the floor (y = 0); end - start has the bar's length
  glm::vec3 across{0.0f};            // unit floor vector along the bar's thickness, towards the camera
  float thickness = 0;               // m, about the same number of pixels whatever the distance
  std::string label;                 // "2 cm"
};

// The bar's length in metres: `bar.metres`, or, when 0, the largest 1, 2 or 5 x 10^k m not above `coinRadius`.
float scaleBarMetres(const ScaleBar& bar, float coinRadius);

// "5 mm", "2 cm", "1.5 m": millimetres under a centimetre, metres from one metre, else centimetres.
std::string scaleBarLabel(float metres);

ScaleBarPlacement placeScaleBar(const ScaleBar& bar, float coinRadius, const CameraView& camera, const CoinPose& coin,
                                int pictureHeight);

}  // namespace coinroll::render
