#include "pipeline/overlay_lines.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "physics/flight.h"

namespace coinroll::pipeline {

namespace {

constexpr double kDegrees = 180 / std::numbers::pi;
constexpr double kTurn = 2 * std::numbers::pi;

// In the air: the coin's plane above the floor (rad, in [0, pi/2], from its axis alone, whichever
// way it has turned over) and the height of the rim's lowest point (m). They follow from the drawn
// pose, which is all FrameState keeps of the attitude: its fixed few bytes bound a clip's memory.
double tiltAboveFloor(const FrameState& frame) {
  const glm::vec3 axis = frame.attitude * glm::vec3(0, 0, 1);
  return std::atan2(std::hypot(static_cast<double>(axis.x), static_cast<double>(axis.z)),
                    std::abs(static_cast<double>(axis.y)));
}
double rimHeight(const physics::CoinModel& model, const FrameState& frame) {
  const Eigen::Quaterniond attitude(frame.attitude.w, frame.attitude.x, frame.attitude.y, frame.attitude.z);
  return frame.centre.y() - physics::lowestPointDepth(model, attitude.normalized());
}

// A value that rounds to zero at `digits` decimals is shown as 0, never as -0.
double shownTo(double value, int digits) { return std::abs(value) < 0.5 * std::pow(10.0, -digits) ? 0.0 : value; }

// The quantities the overlay prints, each as a number in its units and the units' name.
struct Shown {
  double value;
  const char* unit;
};

class Printer {
 public:
  explicit Printer(const OverlayUnits& units) : u_(units) {}

  bool seed() const { return u_.seed; }
  Shown time(double s) const { return u_.seed ? Shown{s / std::sqrt(u_.a / u_.g), "√(a/g)"} : Shown{s, "s"}; }
  // Rates: the seed's radians per its unit of time; in SI turns per second, as the ear hears them.
  Shown rate(double radiansPerSecond) const {
    return u_.seed ? Shown{radiansPerSecond / std::sqrt(u_.g / u_.a), "√(g/a)"}
                   : Shown{radiansPerSecond / kTurn, "Hz"};
  }
  int rateDigits() const { return u_.seed ? 3 : 2; }
  Shown energy(double joules) const {
    return u_.seed ? Shown{joules / (u_.M * u_.g * u_.a), "Mga"} : Shown{joules, "J"};
  }
  // The small numbers: in SI in milli-units at a fixed point, in the seed's four significant digits.
  std::string power(double watts) const {
    return u_.seed ? fmt::format("{:>9} Mg√(ga)", fmt::format("{:.4g}", watts / (u_.M * u_.g * std::sqrt(u_.g * u_.a))))
                   : fmt::format("{:9.3f} mW", 1e3 * watts);
  }
  std::string slip(double metresPerSecond) const {
    return u_.seed ? fmt::format("{:>9} √(ga)", fmt::format("{:.4g}", metresPerSecond / std::sqrt(u_.g * u_.a)))
                   : fmt::format("{:9.2f} mm/s", 1e3 * metresPerSecond);
  }
  std::string height(double metres) const {
    return u_.seed ? fmt::format("{:>9} a", fmt::format("{:.4g}", metres / u_.a))
                   : fmt::format("{:9.2f} mm", 1e3 * metres);
  }

 private:
  OverlayUnits u_;
};

}  // namespace

std::vector<std::string> hudLines(const physics::CoinModel& model, const FrameState& frame,
                                  const std::vector<std::string>& extra, const OverlayUnits& units) {
  // Near flat psi-dot grows with the contact point's rate while the face itself turns slowly, so
  // the overlay names what it shows: Omega = phi-dot (the contact point round the floor, what the ear
  // hears and the eye follows) and the face's own turning omega_Z = psi-dot - phi-dot sin(theta), in
  // the same unit, so that the two rates read side by side. A coin that rocks rather than precesses
  // has no contact rate to show (physics::axisGoesRound).
  // In the air there is no contact and the seed's theta (from vertical, for a coin on its rim) does
  // not say how a tumbling coin lies: the tilt comes from the axis, and the rim's height replaces
  // the contact's rate.
  const Printer p(units);
  const Shown t = p.time(frame.time);
  std::vector<std::string> lines = {fmt::format("t        {:9.3f} {}", t.value, t.unit)};
  const int digits = p.rateDigits();
  if (frame.flying) {
    lines.push_back(fmt::format("tilt     {:9.2f}° above the floor", tiltAboveFloor(frame) * kDegrees));
    lines.push_back(fmt::format("rim      {} above the floor, in the air", p.height(rimHeight(model, frame))));
  } else {
    // The scene's theta (from vertical), and the tilt above the floor a spin-down is read by.
    lines.push_back(fmt::format("θ        {:9.2f}° from vertical, {:.2f}° above the floor",
                                shownTo(frame.theta * kDegrees, 2), 90 - std::abs(frame.theta) * kDegrees));
    const Shown contact = p.rate(std::abs(frame.precessionRate));
    lines.push_back(frame.axisGoesRound
                        ? fmt::format("contact  {:9.{}f} {} round the floor", contact.value, digits, contact.unit)
                        : std::string("contact         -- rocking, not going round"));
  }
  const Shown face = p.rate(frame.omega_Z);
  lines.push_back(fmt::format("face     {:9.{}f} {} about its axis", shownTo(face.value, digits), digits, face.unit));
  const Shown energy = p.energy(frame.energy);
  lines.push_back(fmt::format("E        {:9.5f} {}", energy.value, energy.unit));
  if (!model.effects.empty()) lines.push_back(fmt::format("P        {} dissipated", p.power(frame.power)));
  // What is drawn is what is simulated: a sliding coin says so, with the slip of its contact.
  if (frame.sliding) lines.push_back(fmt::format("sliding  {} slip", p.slip(frame.slipSpeed)));
  // With flight, the phase and the bounces so far (the trace under a flying coin is its rim's lowest
  // point seen from above).
  if (frame.flying || frame.impacts > 0) {
    lines.push_back(fmt::format("{:<8} {:9d} impact{}", frame.flying ? "flight" : "landed", frame.impacts,
                                frame.impacts == 1 ? "" : "s"));
  }
  lines.insert(lines.end(), extra.begin(), extra.end());
  return lines;
}

std::vector<std::string> panelLabel(const physics::CoinModel& model, const FrameState& frame) {
  std::vector<std::string> lines = {fmt::format("t = {:.3f} s", frame.time)};
  if (frame.flying) {
    lines.push_back(fmt::format("{:.2f}° above the floor", tiltAboveFloor(frame) * kDegrees));
    lines.push_back(fmt::format("rim {:.1f} mm up, in the air", 1e3 * rimHeight(model, frame)));
  } else {
    lines.push_back(fmt::format("{:.2f}° above the floor", 90 - std::abs(frame.theta) * kDegrees));
    lines.push_back(fmt::format("contact {:.1f} Hz", std::abs(frame.precessionRate) / kTurn));
  }
  return lines;
}

}  // namespace coinroll::pipeline
