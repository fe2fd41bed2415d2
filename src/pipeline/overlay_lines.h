#pragma once
// The overlay's text: what a frame of `render` and `still` prints in its corner, and what the page
// shows over its view (the WebAssembly core's visual track), from one function.

#include <string>
#include <vector>

#include "physics/coin_model.h"
#include "pipeline/run_record.h"

namespace coinroll::pipeline {

// The units the overlay prints in. SI, as the scene holds them; or the seed's dimensionless units
// M = a = g = 1 (docs/seed.md), in which the rates are the seed's radians per √(a/g), not turns per
// second, and the small numbers (power, slip, the rim's height) take four significant digits.
struct OverlayUnits {
  bool seed = false;
  double M = 1, a = 1, g = 1;  // kg, m, m/s²: the seed's units, those of the run's coin

  static OverlayUnits si() { return {}; }
  static OverlayUnits seedOf(const physics::CoinModel& model) { return {true, model.M, model.a, model.g}; }
};

// The overlay's lines, joined by '\n' and appended to `out`: time, tilt, the contact point's rate
// (in the air: the rim's height), the face's spin, energy (and power dissipated, and the slip while
// sliding, and the impacts).
void writeHud(std::string& out, const physics::CoinModel& model, const FrameState& frame,
              const OverlayUnits& units = OverlayUnits::si());

// writeHud's lines one by one, then `extra`.
std::vector<std::string> hudLines(const physics::CoinModel& model, const FrameState& frame,
                                  const std::vector<std::string>& extra = {},
                                  const OverlayUnits& units = OverlayUnits::si());

// A strobe panel's short overlay (still --panels), instead of the full overlay that would cover a
// third of a small panel: the time, the tilt above the floor, and on the floor the contact point's
// rate, in the air the rim's height (hudLines says the same in its longer form).
std::vector<std::string> panelLabel(const physics::CoinModel& model, const FrameState& frame);

}  // namespace coinroll::pipeline
