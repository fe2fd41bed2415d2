#include "render/theme.h"

namespace coinroll::render {

namespace {

const Palette kClassic{
    .backgroundSrgb = {0.86f, 0.89f, 0.93f},
    .floor = {.floor = {0.25f, 0.26f, 0.28f}, .minorLine = {0.35f, 0.36f, 0.38f}, .majorLine = {0.45f, 0.47f, 0.50f}},
    // Deep blue for old, orange-red for new, so the direction of travel and the recent path both
    // read; where the coin slid, yellow fading to pale green.
    .trace = {.recentRolling = {0.93f, 0.33f, 0.08f},
              .oldRolling = {0.30f, 0.52f, 0.95f},
              .recentSliding = {0.98f, 0.84f, 0.10f},
              .oldSliding = {0.55f, 0.90f, 0.55f},
              .opacity = {0.95f, 0.25f}},
    .overlay = {.ink = {0.97f, 0.97f, 0.95f, 1.0f}, .panel = {0.08f, 0.09f, 0.11f, 0.62f}},
    .scaleBar = {0.97f, 0.97f, 0.95f, 1.0f},
};

// On paper the grid is dark on white, and every trace colour is dark enough to keep its contrast
// against white in grey print (lightness at most about 55 %), old points fading less than on a
// dark floor, where pale still shows.
const Palette kPaper{
    .backgroundSrgb = {1.0f, 1.0f, 1.0f},
    .floor = {.floor = {0.90f, 0.90f, 0.90f}, .minorLine = {0.45f, 0.46f, 0.48f}, .majorLine = {0.12f, 0.12f, 0.13f}},
    .trace = {.recentRolling = {0.75f, 0.08f, 0.04f},
              .oldRolling = {0.08f, 0.20f, 0.62f},
              .recentSliding = {0.85f, 0.45f, 0.00f},
              .oldSliding = {0.05f, 0.45f, 0.15f},
              .opacity = {0.95f, 0.50f}},
    .overlay = {.ink = {0.06f, 0.06f, 0.08f, 1.0f}, .panel = {1.0f, 1.0f, 1.0f, 0.80f}},
    .scaleBar = {0.05f, 0.05f, 0.06f, 1.0f},
};

}  // namespace

const Palette& palette(Theme theme) { return theme == Theme::Paper ? kPaper : kClassic; }

}  // namespace coinroll::render
