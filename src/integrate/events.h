#pragma once
// Scalar events g(t, y) = 0, located on the dense output of the step where g changes sign.

#include <functional>
#include <string>

#include "integrate/solver_config.h"

namespace coinroll::integrate {

template <int N>
struct Event {
  std::string name;  // e.g. "lift-off", for messages
  int id = 0;        // the caller's own identity for the event (an enum's value): compared, never the name
  std::function<double(double t, const Vec<N>& y)> g;  // the event is a root of g
  int direction = 0;                                   // 0 any crossing, +1 only g rising through 0, -1 only falling
  bool terminal = true;                                // stop the run at the root
  // g is also read at this many evenly spaced points inside each step, on the dense output: a
  // crossing there and back within one step (a friction cone grazed for a millisecond) shows no
  // sign change at the step's ends. Each point costs one g; 0 checks the ends only.
  int interiorChecks = 0;
  // g's rate dg/dt (or any function with its sign and its zeros), where the state gives it cheaply:
  // a dip of g to the far side of zero and back within one step, which neither the ends nor the
  // interior points see, has an extremum where this changes sign; it is located there and read.
  std::function<double(double t, const Vec<N>& y)> rate = nullptr;
};

template <int N>
struct EventHit {
  std::string name;
  int id = 0;
  double t = 0;  // s
  Vec<N> y;
};

}  // namespace coinroll::integrate
