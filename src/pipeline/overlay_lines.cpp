#include "pipeline/overlay_lines.h"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <numbers>
#include <string_view>
#include <utility>

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

// Writes the overlay's lines into one buffer, each after a '\n' but the first. A page's visual track
// formats two overlays for every row of a run, which cost 11 times the run itself on steady_circle
// (598 M instructions against 55 M over 20 runs) when each line was a string of its own, joined,
// and fmt parsed its format at every call and wrote through a std::string's back_inserter (a second
// buffer and a copy). Compiled formats into one memory_buffer: 258 M; the rest is fmt's exact
// fixed-point formatting of the numbers.
class Writer {
 public:
  explicit Writer(const OverlayUnits& units) : u_(units) {}

  // `format`: FMT_COMPILE's, parsed when compiled rather than at every line.
  template <typename Format, typename... Args>
  void line(const Format& format, Args&&... args) {
    if (out_.size() > 0) out_.push_back('\n');
    fmt::format_to(fmt::appender(out_), format, std::forward<Args>(args)...);
  }
  void appendTo(std::string& text) const { text.append(out_.data(), out_.size()); }

  Shown time(double s) const { return u_.seed ? Shown{s / std::sqrt(u_.a / u_.g), "√(a/g)"} : Shown{s, "s"}; }
  // Rates: the seed's radians per its unit of time; in SI turns per second, as the ear hears them.
  Shown rate(double radiansPerSecond) const {
    return u_.seed ? Shown{radiansPerSecond / std::sqrt(u_.g / u_.a), "√(g/a)"} : Shown{radiansPerSecond / kTurn, "Hz"};
  }
  int rateDigits() const { return u_.seed ? 3 : 2; }
  Shown energy(double joules) const {
    return u_.seed ? Shown{joules / (u_.M * u_.g * u_.a), "Mga"} : Shown{joules, "J"};
  }
  // The small numbers: in SI in milli-units at a fixed point, in the seed's four significant digits,
  // right-aligned in the same nine characters.
  void smallLine(const char* label, double si, double seedUnit, const char* seedName, int siDigits, const char* siName,
                 const char* after) {
    if (u_.seed) {
      const fmt::memory_buffer number = formatted(si / seedUnit);
      line(FMT_COMPILE("{:<8} {:>9} {} {}"), label, std::string_view(number.data(), number.size()), seedName, after);
    } else {
      line(FMT_COMPILE("{:<8} {:9.{}f} {} {}"), label, 1e3 * si, siDigits, siName, after);
    }
  }
  double powerUnit() const { return u_.M * u_.g * std::sqrt(u_.g * u_.a); }
  double speedUnit() const { return std::sqrt(u_.g * u_.a); }
  double lengthUnit() const { return u_.a; }

 private:
  static fmt::memory_buffer formatted(double value) {
    fmt::memory_buffer number;
    fmt::format_to(fmt::appender(number), FMT_COMPILE("{:.4g}"), value);
    return number;
  }

  fmt::memory_buffer out_;
  OverlayUnits u_;
};

}  // namespace

void writeHud(std::string& out, const physics::CoinModel& model, const FrameState& frame, const OverlayUnits& units) {
  // Near flat psi-dot grows with the contact point's rate while the face itself turns slowly, so
  // the overlay names what it shows: Omega = phi-dot (the contact point round the floor, what the ear
  // hears and the eye follows) and the face's own turning omega_Z = psi-dot - phi-dot sin(theta), in
  // the same unit, so that the two rates read side by side. A coin that rocks rather than precesses
  // has no contact rate to show (physics::axisGoesRound).
  // In the air there is no contact and the seed's theta (from vertical, for a coin on its rim) does
  // not say how a tumbling coin lies: the tilt comes from the axis, and the rim's height replaces
  // the contact's rate.
  Writer w(units);
  const Shown t = w.time(frame.time);
  w.line(FMT_COMPILE("t        {:9.3f} {}"), t.value, t.unit);
  const int digits = w.rateDigits();
  if (frame.flying) {
    w.line(FMT_COMPILE("tilt     {:9.2f}° above the floor"), tiltAboveFloor(frame) * kDegrees);
    w.smallLine("rim", rimHeight(model, frame), w.lengthUnit(), "a", 2, "mm", "above the floor, in the air");
  } else {
    // The scene's theta (from vertical), and the tilt above the floor a spin-down is read by.
    w.line(FMT_COMPILE("θ        {:9.2f}° from vertical, {:.2f}° above the floor"), shownTo(frame.theta * kDegrees, 2),
           90 - std::abs(frame.theta) * kDegrees);
    const Shown contact = w.rate(std::abs(frame.precessionRate));
    if (frame.axisGoesRound) {
      w.line(FMT_COMPILE("contact  {:9.{}f} {} round the floor"), contact.value, digits, contact.unit);
    } else {
      w.line(FMT_COMPILE("contact         -- rocking, not going round"));
    }
  }
  const Shown face = w.rate(frame.omega_Z);
  w.line(FMT_COMPILE("face     {:9.{}f} {} about its axis"), shownTo(face.value, digits), digits, face.unit);
  const Shown energy = w.energy(frame.energy);
  w.line(FMT_COMPILE("E        {:9.5f} {}"), energy.value, energy.unit);
  if (!model.effects.empty()) w.smallLine("P", frame.power, w.powerUnit(), "Mg√(ga)", 3, "mW", "dissipated");
  // What is drawn is what is simulated: a sliding coin says so, with the slip of its contact.
  if (frame.sliding) w.smallLine("sliding", frame.slipSpeed, w.speedUnit(), "√(ga)", 2, "mm/s", "slip");
  // With flight, the phase and the bounces so far (the trace under a flying coin is its rim's lowest
  // point seen from above).
  if (frame.flying || frame.impacts > 0) {
    w.line(FMT_COMPILE("{:<8} {:9d} impact{}"), frame.flying ? "flight" : "landed", frame.impacts,
           frame.impacts == 1 ? "" : "s");
  }
  w.appendTo(out);
}

std::vector<std::string> hudLines(const physics::CoinModel& model, const FrameState& frame,
                                  const std::vector<std::string>& extra, const OverlayUnits& units) {
  std::string text;
  writeHud(text, model, frame, units);
  std::vector<std::string> lines;
  for (std::size_t from = 0;;) {
    const std::size_t to = text.find('\n', from);
    lines.emplace_back(text, from, to == std::string::npos ? std::string::npos : to - from);
    if (to == std::string::npos) break;
    from = to + 1;
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
