// The overlay's contact rate against the motion it names: a precessing coin's Omega in Hz, and no
// number for a coin that rocks through flat (whose phi-dot is a kHz whip of its heading); in the air,
// no contact at all but the rim's height, and the tilt of a tumbling coin from its axis.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "pipeline/overlay_lines.h"
#include "pipeline/snapshot.h"
#include "render/camera.h"
#include "render/overlay_text.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

std::string contactLine(const nlohmann::json& doc, double time) {
  const scene::SceneConfig scene = scene::parseScene(doc, "test");
  const pipeline::Simulation sim = pipeline::buildSimulation(scene);
  pipeline::FixedFrameTimes at({time});
  const pipeline::RunRecord record = pipeline::recordRun(sim, at);
  pipeline::SnapshotMaker maker(scene, sim.model, record);
  for (const std::string& line : maker.makeSnapshot(record.frames.at(0)).hudLines) {
    if (line.starts_with("contact")) return line;
  }
  return {};
}

}  // namespace

TEST(Overlay, AnEulersDiskSpinningInPlaceShowsItsContactRateInHertz) {
  // A thin disk spinning in place at theta from vertical has I_X omega_Y^2 = M g a cos(theta)
  // (docs/derivations.md), so Omega = omega_Y / cos(theta) = sqrt(4 g / (a cos(theta))): the rate shown.
  const double a = 0.0375, g = 9.81, theta = 75 * std::numbers::pi / 180;
  const nlohmann::json doc = {{"coin", {{"radius", a}, {"mass", 0.4}}},
                              {"initial", {{"steady", "spin-in-place"}, {"theta", 75}}},
                              {"duration", 0.5}};
  const double omega = std::sqrt(4 * g / (a * std::cos(theta)));
  EXPECT_EQ(contactLine(doc, 0.25), fmt::format("contact  {:9.2f} Hz round the floor", omega / (2 * std::numbers::pi)));
}

TEST(Overlay, ACoinRockingThroughFlatShowsNoContactRate) {
  // falling_flat: released at 60 deg without spin, it rocks between 60 and about 89 deg; near flat
  // its heading whips round at hundreds of Hz while nothing circles the floor.
  const nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
                              {"initial", {{"theta", 60}, {"omega_Z", 0.1}}},
                              {"duration", 0.2},
                              {"solver", {{"formulation", "quaternion"}}}};
  for (const double t : {0.04, 0.08, 0.12, 0.16}) {
    EXPECT_EQ(contactLine(doc, t), "contact         -- rocking, not going round") << "t = " << t;
  }
}

namespace {

// The coin toss's first 0.2 s, all in the air (examples/coin_toss.json): launched at theta = -89 deg,
// nearly flat, it turns over about its diameter at 6 turns a second.
struct Toss {
  scene::SceneConfig scene = scene::loadScene(std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json", {});
  pipeline::Simulation sim = pipeline::buildSimulation(scene);
  pipeline::FixedFrameTimes times{{0, 0.05, 0.1, 0.15, 0.2}};
  pipeline::RunRecord record = pipeline::recordRun(sim, times);
};

// Degrees, the coin's plane above the floor from the drawn attitude, and the height of its lowest
// point (mm) from the flight's own geometry: not the numbers the overlay reads.
double tiltDegrees(const pipeline::FrameState& frame) {
  const glm::vec3 axis = frame.attitude * glm::vec3(0, 0, 1);
  return std::acos(std::min(1.0, std::abs(static_cast<double>(axis.y)))) * 180 / std::numbers::pi;
}
// The toss's coin (radius a, thickness h, edge radius rho) is a disk of radius a - rho and thickness
// h - 2 rho swollen by a ball of radius rho: at a tilt alpha its lowest point lies
// (a - rho) sin(alpha) + (h / 2 - rho) cos(alpha) + rho below the centre.
double rimMillimetres(const pipeline::FrameState& frame) {
  constexpr double a = 0.01213, h = 0.00175, rho = 0.0003;  // m, examples/coin_toss.json
  const double alpha = tiltDegrees(frame) * std::numbers::pi / 180;
  return 1e3 * (frame.centre.y() - ((a - rho) * std::sin(alpha) + (h / 2 - rho) * std::cos(alpha) + rho));
}

// The number after `label` in `line`.
double numberAfter(const std::string& line, std::string_view label) {
  return line.starts_with(label) ? std::stod(line.substr(label.size())) : std::nan("");
}

}  // namespace

TEST(Overlay, ACoinInTheAirShowsItsTiltAndRimHeightAndNoContact) {
  const Toss toss;
  for (const pipeline::FrameState& frame : toss.record.frames) {
    ASSERT_TRUE(frame.flying) << "t = " << frame.time;
    pipeline::SnapshotMaker maker(toss.scene, toss.sim.model, toss.record);
    const std::vector<std::string> hud = maker.makeSnapshot(frame).hudLines;
    const auto lineStarting = [&](std::string_view start) {
      const auto found = std::ranges::find_if(hud, [&](const std::string& l) { return l.starts_with(start); });
      return found == hud.end() ? std::string() : *found;
    };
    EXPECT_EQ(lineStarting("contact"), "") << "t = " << frame.time;
    EXPECT_EQ(lineStarting("tilt"), fmt::format("tilt     {:9.2f}° above the floor", tiltDegrees(frame)))
        << "t = " << frame.time;
    const std::string rim = lineStarting("rim");
    EXPECT_TRUE(rim.ends_with(" mm above the floor, in the air")) << rim;
    EXPECT_NEAR(numberAfter(rim, "rim"), rimMillimetres(frame), 0.006) << "t = " << frame.time;
  }
}

TEST(Overlay, AStrobePanelOfACoinInTheAirShowsItsTiltAndRimHeight) {
  const Toss toss;
  for (const pipeline::FrameState& frame : toss.record.frames) {
    const std::vector<std::string> label = pipeline::panelLabel(toss.sim.model, frame);
    ASSERT_EQ(label.size(), 3u);
    EXPECT_EQ(label[1], fmt::format("{:.2f}° above the floor", tiltDegrees(frame))) << "t = " << frame.time;
    EXPECT_TRUE(label[2].ends_with(" mm up, in the air")) << label[2];
    EXPECT_NEAR(numberAfter(label[2], "rim"), rimMillimetres(frame), 0.06) << "t = " << frame.time;
  }
}

TEST(Overlay, AStrobePanelOfACoinOnTheFloorShowsItsTiltAndContactRate) {
  // Leaning either way, theta = +-20 deg is 70 deg above the floor.
  for (const int theta : {20, -20}) {
    const nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
                                {"initial", {{"steady", "spin-in-place"}, {"theta", theta}}},
                                {"duration", 0.5}};
    const scene::SceneConfig scene = scene::parseScene(doc, "test");
    pipeline::FixedFrameTimes at({0.25});
    const pipeline::RunRecord record = pipeline::recordRun(pipeline::buildSimulation(scene), at);
    const pipeline::FrameState& frame = record.frames.at(0);
    EXPECT_EQ(pipeline::panelLabel(pipeline::buildSimulation(scene).model, frame),
              (std::vector<std::string>{
                  "t = 0.250 s", "70.00° above the floor",
                  fmt::format("contact {:.1f} Hz", std::abs(frame.precessionRate) / (2 * std::numbers::pi))}))
        << "theta = " << theta;
  }
}

TEST(StrobeFraming, AFollowedTossIsSeenWholeBelowTheOverlay) {
  // still examples/coin_toss.json --time 0.5 --strobe 20: the follow camera looks at the last copy
  // only, back on the floor after the first bounces, and the arc (up to 0.37 m: 0.3 m + v_y^2 / 2g)
  // is out of its picture.
  scene::SceneConfig scene = scene::loadScene(std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json", {});
  constexpr int kWidth = 854, kHeight = 480;
  scene.render.picture.width = kWidth;
  scene.render.picture.height = kHeight;
  const pipeline::Simulation sim = pipeline::buildSimulation(scene);
  std::vector<double> times;
  for (int i = 0; i <= 20; ++i) times.push_back(0.025 * i);
  pipeline::FixedFrameTimes at(times);
  const pipeline::RunRecord record = pipeline::recordRun(sim, at);
  const std::vector<std::string> legend = {"copies      20 every 25 ms", "grid        10 mm squares"};
  pipeline::SnapshotMaker maker(scene, sim.model, record);
  maker.frameCopies(record.frames, legend);
  const render::FrameSnapshot& shown = maker.makeSnapshot(record.frames.back(), legend);
  // The overlay's box as the renderer lays it out: half a line's margin, then the text panel.
  const render::GlyphAtlas atlas(render::overlayTextPixels(kHeight));
  const float overlayBottom = std::round(0.5f * atlas.lineHeight()) + render::textPanelSize(atlas, shown.hudLines).y;
  // Each copy's disk reaches a radius from its centre, whichever way it faces: the points a radius
  // along the view's right and up (and down and left) must be in the picture and below the overlay.
  const glm::vec3 forward = glm::normalize(shown.camera.target - shown.camera.eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  const float a = static_cast<float>(sim.model.a);
  for (const pipeline::FrameState& frame : record.frames) {
    const glm::vec3 centre(frame.centre.x(), frame.centre.y(), frame.centre.z());
    for (const glm::vec3& reach : {a * right, -a * right, a * up, -a * up}) {
      const glm::vec2 pixel = render::pixelFromWorld(shown.camera, kWidth, kHeight, centre + reach);
      EXPECT_TRUE(pixel.x >= 0 && pixel.x <= kWidth && pixel.y >= overlayBottom && pixel.y <= kHeight)
          << "t = " << frame.time << " s: the coin's edge at pixel (" << pixel.x << ", " << pixel.y
          << "), the overlay down to " << overlayBottom;
    }
  }
}
