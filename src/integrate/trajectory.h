#pragma once
// The streaming driver: integrates forward on demand and answers "state at t" from the dense
// output of the step containing t, so samples land exactly on t_k = k S (no stepping to sample
// times, no restarts), and locates events on the same dense output.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "integrate/dop853.h"
#include "integrate/event_location.h"
#include "integrate/events.h"
#include "integrate/gauss_legendre.h"
#include "integrate/pace.h"
#include "integrate/solver_config.h"
#include "integrate/steppers.h"

namespace coinroll::integrate {

template <int N, class Rhs>
class Trajectory {
 public:
  Trajectory(Rhs f, double t0, const Vec<N>& y0, const SolverConfig& config, std::vector<Event<N>> events = {})
      : f_(std::move(f)),
        config_(config),
        events_(std::move(events)),
        t_(t0),
        pace_(t0, config.endTime, config.maxSteps),
        y_(y0) {
    validate();
    f0_ = evaluate(t_, y_);
    for (const Event<N>& e : events_) {
      gAtStart_.push_back(e.g(t_, y_));
      rateAtStart_.push_back(e.rate ? e.rate(t_, y_) : 0.0);
    }
    h_ = isAdaptive(config_.method) ? initialStep() : config_.dt;
    interval_ = hermiteInterval<N>(t_, 0.0, y_, f0_, y_, f0_);
  }

  // State at t >= every earlier query. std::nullopt once a terminal event has stopped the run
  // before t; stoppedBy() then names it.
  std::optional<Vec<N>> stateAt(double t) {
    if (t < lastQuery_) {
      throw std::logic_error(
          fmt::format("Trajectory::stateAt: queries must not go back in time ({} after {})", t, lastQuery_));
    }
    lastQuery_ = t;
    while (t > t_ && !stoppedBy_) advance();
    if (stoppedBy_ && t > stoppedBy_->t) return std::nullopt;
    if (t == t_) return y_;
    return interval().at(t);
  }

  const std::optional<EventHit<N>>& stoppedBy() const { return stoppedBy_; }
  const std::vector<EventHit<N>>& nonTerminalHits() const { return nonTerminalHits_; }
  const Stats& stats() const { return stats_; }
  double time() const { return t_; }  // s, end of the last accepted step

 private:
  Vec<N> evaluate(double t, const Vec<N>& y) {
    ++stats_.rhsEvaluations;
    return f_(t, y);
  }

  void validate() const {
    const bool adaptive = isAdaptive(config_.method);
    if (adaptive && !(config_.rtol > 0 && config_.atol >= 0)) {
      throw std::invalid_argument(
          fmt::format("solver: rtol must be > 0 and atol >= 0, got {} and {}", config_.rtol, config_.atol));
    }
    if (!adaptive && !(config_.dt > 0 && std::isfinite(config_.dt))) {
      throw std::invalid_argument(fmt::format("solver.dt: must be a finite step > 0 s, got {}", config_.dt));
    }
    if (!y_.allFinite()) throw std::invalid_argument("initial state has a non-finite component");
  }

  // Hairer-Norsett-Wanner's weighted RMS norm of a local error.
  double errorNorm(const Vec<N>& error, const Vec<N>& y0, const Vec<N>& y1) const {
    const Vec<N> scale = (config_.atol + config_.rtol * y0.cwiseAbs().cwiseMax(y1.cwiseAbs()).array()).matrix();
    return std::sqrt((error.cwiseQuotient(scale)).squaredNorm() / N);
  }

  // HNW's starting step: make the first step's Euler error about 1 % of the tolerance.
  double initialStep() {
    const Vec<N> scale = (config_.atol + config_.rtol * y_.cwiseAbs().array()).matrix();
    const double d0 = std::sqrt(y_.cwiseQuotient(scale).squaredNorm() / N);
    const double d1 = std::sqrt(f0_.cwiseQuotient(scale).squaredNorm() / N);
    double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    h0 = std::min(h0, config_.maxStep);
    const Vec<N> f1 = evaluate(t_ + h0, Vec<N>(y_ + h0 * f0_));
    const double d2 = std::sqrt((f1 - f0_).cwiseQuotient(scale).squaredNorm() / N) / h0;
    const double d = std::max(d1, d2);
    const double order = errorEstimateOrder(config_.method);
    const double h1 = d <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / d, 1.0 / order);
    return std::min({100 * h0, h1, config_.maxStep});
  }

  void advance() {
    const double tStart = t_;
    if (isAdaptive(config_.method)) {
      adaptiveStep();
    } else {
      // Fixed steps sit on the grid t0 + k dt so step points do not drift with round-off.
      const double tNext = gridOrigin_ + static_cast<double>(stats_.acceptedSteps + 1) * config_.dt;
      const double h = tNext - t_;
      const Vec<N> y1 = fixedStep(h);
      const Vec<N> f1 = evaluate(tNext, y1);
      interval_ = hermiteInterval<N>(t_, h, y_, f0_, y1, f1);
      if (config_.method == Method::Euler) {  // the chord: Euler's slope at t1 is not its own
        interval_.r3.setZero();
        interval_.r4.setZero();
      }
      accept(tNext, y1, f1);
    }
    checkEvents(tStart);
  }

  Vec<N> fixedStep(double h) {
    switch (config_.method) {
      case Method::Rk4: stats_.rhsEvaluations += 3; return rk4Step<N>(f_, t_, y_, f0_, h);
      case Method::Gauss4: return gauss4_.step(f_, t_, y_, f0_, h, stats_.rhsEvaluations);
      case Method::Euler: return eulerStep<N>(f_, t_, y_, f0_, h);
      case Method::Dopri5:
      case Method::Dop853: break;
    }
    throw std::logic_error(fmt::format("{} is not a fixed-step method", nameOf(config_.method)));
  }

  // Step-size control of HNW's codes (Solving ODEs I, II.4; the PI form in II, IV.2): the next
  // step is h err^-exponent prev_err^beta times the safety factor, growth per step bounded. DOPRI5
  // keeps HNW's beta = 0.04. DOP853 ships with beta = 0 (plain I control), which on the coin
  // rejects 15-20 % of its steps at rtol 1e-6..1e-10, each wasting 12 stages; beta = 0.08
  // (exponent 1/8 - 0.2 beta as in DOP853's code) rejects none and needs 15 % fewer
  // evaluations for the same global error at 1e-8 and 1e-10 (bench/work_precision, wobble1000).
  struct Controller {
    double beta, exponent, minFactor, maxFactor;
  };
  static constexpr Controller kDopri5Controller{0.04, 0.2 - 0.04 * 0.75, 0.2, 10.0};
  static constexpr Controller kDop853Controller{0.08, 1.0 / 8 - 0.2 * 0.08, 0.333, 6.0};
  static constexpr double kSafety = 0.9;

  void adaptiveStep() {
    const bool dop853 = config_.method == Method::Dop853;
    const Controller& c = dop853 ? kDop853Controller : kDopri5Controller;
    bool lastRejected = false;
    while (true) {
      const double h = std::min(h_, config_.maxStep);
      if (!(h > 1e-14 * std::max(1.0, std::abs(t_)))) {
        throw std::runtime_error(
            fmt::format("integration stalled: step size {} s at t = {} s, state ({})", h, t_, describe(y_)));
      }
      double err;
      if (dop853) {
        const Dop853Result<N> r = dop853Step<N>(f_, t_, y_, f0_, h);
        stats_.rhsEvaluations += 12;
        err = dop853ErrorNorm(r, h);
        if (err <= 1.0 && std::isfinite(err)) {
          pendingInterval_ = PendingDop853Interval{t_, h, y_, f0_, r};
          finishAcceptedStep(c, err, h, lastRejected, r.y1, r.f1);
          return;
        }
      } else {
        const Dopri5Result<N> r = dopri5Step<N>(f_, t_, y_, f0_, h);
        stats_.rhsEvaluations += 6;
        err = errorNorm(r.error, y_, r.y1);
        if (err <= 1.0 && std::isfinite(err)) {
          interval_ = dopri5Interval<N>(t_, h, y_, f0_, r);
          finishAcceptedStep(c, err, h, lastRejected, r.y1, r.f1);
          return;
        }
      }
      ++stats_.rejectedSteps;
      lastRejected = true;
      h_ = std::isfinite(err) ? h / std::min(1 / c.minFactor, std::pow(err, c.exponent) / kSafety) : h * c.minFactor;
    }
  }

  void finishAcceptedStep(const Controller& c, double err, double h, bool lastRejected, const Vec<N>& y1,
                          const Vec<N>& f1) {
    double factor = std::pow(err, c.exponent) / std::pow(previousError_, c.beta) / kSafety;
    factor = std::clamp(factor, 1 / c.maxFactor, 1 / c.minFactor);
    double hNew = h / factor;
    if (lastRejected) hNew = std::min(hNew, h);  // HNW: no growth right after a rejection
    previousError_ = std::max(err, 1e-4);
    h_ = hNew;
    accept(t_ + h, y1, f1);
  }

  // DOP853's combined norm: the 5th-order estimate, damped where the 3rd-order one says the
  // 5th is pessimistic (HNW II.10, "err = |h| err5^2 / sqrt(err5^2 + 0.01 err3^2)").
  double dop853ErrorNorm(const Dop853Result<N>& r, double h) const {
    const Vec<N> scale = (config_.atol + config_.rtol * y_.cwiseAbs().cwiseMax(r.y1.cwiseAbs()).array()).matrix();
    const double err5 = r.error5.cwiseQuotient(scale).squaredNorm();
    const double err3 = r.error3.cwiseQuotient(scale).squaredNorm();
    double denominator = err5 + 0.01 * err3;
    if (denominator <= 0) denominator = 1;
    return std::abs(h) * err5 / std::sqrt(N * denominator);
  }

  void accept(double t1, const Vec<N>& y1, const Vec<N>& f1) {
    if (!y1.allFinite()) {
      throw std::runtime_error(
          fmt::format("integration produced a non-finite state at t = {} s (from {})", t1, describe(y_)));
    }
    const double previousT = t_;
    t_ = t1;
    y_ = y1;
    f0_ = f1;
    if (++stats_.acceptedSteps > config_.maxSteps) {
      throw std::runtime_error(
          fmt::format("integration needs more than {} steps: stopped at t = {} s, h = {} s, state ({})",
                      config_.maxSteps, t_, t1 - previousT, describe(y_)));
    }
    pace_.afterSteps(stats_.acceptedSteps, t_);
  }

  static bool crosses(const Event<N>& e, double gFrom, double gTo) {
    const bool rising = gFrom < 0 && gTo >= 0, falling = gFrom > 0 && gTo <= 0;
    return (e.direction >= 0 && rising) || (e.direction <= 0 && falling);
  }

  void checkEvents(double tStart) {
    std::optional<EventHit<N>> earliestTerminal;
    for (std::size_t i = 0; i < events_.size(); ++i) {
      const Event<N>& e = events_[i];
      double from = tStart, gFrom = gAtStart_[i];
      const double gEnd = e.g(t_, y_);
      gAtStart_[i] = gEnd;
      // The first sub-interval whose ends cross: the interior points' in time order, then the last.
      double to = t_, gTo = gEnd;
      bool crossed = false;
      for (int k = 1; k <= e.interiorChecks && !crossed; ++k) {
        const double t = tStart + (t_ - tStart) * k / (e.interiorChecks + 1);
        const double g = e.g(t, interval().at(t));
        if (crosses(e, gFrom, g)) {
          to = t, gTo = g, crossed = true;
        } else {
          from = t, gFrom = g;
        }
      }
      const double rateFrom = rateAtStart_[i];
      if (e.rate) rateAtStart_[i] = e.rate(t_, y_);
      if (!crossed && !crosses(e, gFrom, gEnd)) {
        // No sign change: an extremum between the step's ends may still reach the far side of zero.
        // Only the whole step's ends are compared: with interior points the dip is between two of
        // them, and their rates are not read.
        if (!e.rate || e.interiorChecks > 0) continue;
        const double rateEnd = rateAtStart_[i];
        const bool dip = e.direction <= 0 && gFrom > 0 && gEnd > 0 && rateFrom < 0 && rateEnd > 0;
        const bool peak = e.direction >= 0 && gFrom < 0 && gEnd < 0 && rateFrom > 0 && rateEnd < 0;
        if (!dip && !peak) continue;
        const double tExtremum =
            locateRoot([&](double t) { return e.rate(t, interval().at(t)); }, from, rateFrom, t_, rateEnd);
        const double gExtremum = e.g(tExtremum, interval().at(tExtremum));
        if (!crosses(e, gFrom, gExtremum)) continue;
        to = tExtremum, gTo = gExtremum;
      }
      const double tRoot = locateRoot([&](double t) { return e.g(t, interval().at(t)); }, from, gFrom, to, gTo);
      EventHit<N> hit{e.name, e.id, tRoot, interval().at(tRoot)};
      if (!e.terminal) {
        nonTerminalHits_.push_back(hit);
      } else if (!earliestTerminal || tRoot < earliestTerminal->t) {
        earliestTerminal = hit;
      }
    }
    if (earliestTerminal) stoppedBy_ = earliestTerminal;
  }

  // The dense output of the last step. DOP853's 7th-order interpolant costs three more stages;
  // they are evaluated only when a query or an event root falls inside the step, which most
  // steps of a long run with sparse output never see (about a sixth of the evaluations).
  const DenseInterval<N>& interval() {
    if (pendingInterval_) {
      const PendingDop853Interval& p = *pendingInterval_;
      interval_ = dop853Interval<N>(f_, p.t0, p.h, p.y0, p.k1, p.stages);
      stats_.rhsEvaluations += 3;
      pendingInterval_.reset();
    }
    return interval_;
  }

  static std::string describe(const Vec<N>& y) {
    std::ostringstream text;
    text << y.transpose();
    return text.str();
  }

  Rhs f_;
  SolverConfig config_;
  std::vector<Event<N>> events_;
  std::vector<double> gAtStart_;     // each event's g at the start of the current step
  std::vector<double> rateAtStart_;  // and its rate, for the events that give one
  double t_;                         // s, end of the last accepted step
  PaceWatch pace_;                   // measured from the run's start
  Vec<N> y_, f0_;                    // state and slope at t_
  double gridOrigin_ = t_;           // s, origin of the fixed-step grid
  double h_ = 0;                     // s, next step to try
  double previousError_ = 1e-4;      // PI controller memory
  double lastQuery_ = -std::numeric_limits<double>::infinity();
  DenseInterval<N> interval_;
  struct PendingDop853Interval {
    double t0, h;  // s
    Vec<N> y0, k1;
    Dop853Result<N> stages;
  };
  std::optional<PendingDop853Interval> pendingInterval_;  // set: interval_ is stale
  GaussLegendre4<N> gauss4_;  // Newton's Jacobian and starting guess carry over between steps
  Stats stats_;
  std::optional<EventHit<N>> stoppedBy_;
  std::vector<EventHit<N>> nonTerminalHits_;
};

}  // namespace coinroll::integrate
