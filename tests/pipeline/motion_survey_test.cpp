// The motion survey against a motion known in closed form: an upright coin spinning about its
// axle rolls in a straight line at speed a omega, so its centre of mass and contact point sweep a
// segment of length a omega T, whatever the survey's sample spacing.

#include <gtest/gtest.h>

#include <cmath>
#include <string_view>
#include <vector>

#include "pipeline/motion_survey.h"
#include "pipeline/simulation.h"
#include "scene/scene_loader.h"
#include "tolerance.h"

namespace {

using namespace coinroll;
using coinroll::testing::isNear;

constexpr double kRadius = 0.0375, kSpin = 14.0;  // m, rad/s: above sqrt(g / 3a) = 9.3, so upright rolling is stable

pipeline::Simulation uprightRoller(double duration) {
  nlohmann::json doc = {
      {"coin", {{"radius", kRadius}, {"mass", 0.4}}},
      {"initial", {{"theta", 0}, {"omega_Z", kSpin}}},
      {"duration", duration},
      {"solver", {{"rtol", 1e-12}, {"atol", 1e-14}}},
  };
  return pipeline::buildSimulation(scene::parseScene(doc, "test"));
}

TEST(SurveyMotion, BoxSpansTheWholeStraightRollUpToItsLastInstant) {
  // Durations off the survey's 1/240 s grid, so the run's last instant is a sample of its own.
  for (const double duration : {1.0 + 1.0 / 480, 2.7, 0.013}) {
    const pipeline::MotionSurvey survey = pipeline::surveyMotion(uprightRoller(duration));
    const double rolled = kRadius * kSpin * duration;
    // y is up; the segment's bounding box has the segment for its horizontal (x, z) diagonal.
    const Eigen::Vector3d extent = survey.upper - survey.lower;
    EXPECT_TRUE(isNear(std::hypot(extent.x(), extent.z()), rolled, 1e-9)) << "duration " << duration;
    EXPECT_TRUE(isNear(survey.lower.y(), 0.0, 1e-12)) << "the contact point is on the floor";
    EXPECT_TRUE(isNear(survey.upper.y(), kRadius, 1e-12)) << "the centre of mass is a radius above it";
    EXPECT_EQ(survey.endTime, duration);
    EXPECT_FALSE(survey.stoppedBy.has_value());
  }
}

}  // namespace
