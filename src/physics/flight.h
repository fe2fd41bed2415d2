#pragma once
// The coin between contacts (docs/flight.md): a free rigid body under gravity, torque-free about
// its centre of mass, and the gap between its rim's lowest point and the floor that ends a flight.
// The attitude is the quaternion formulation's, so a flight continues a rolling or sliding segment
// and hands back to one without a change of variables.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/forward.h"

namespace coinroll::physics {

struct FlightState {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // unit, floor from body
  Eigen::Vector3d omegaBody = Eigen::Vector3d::Zero();    // rad/s, material axes
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();       // m, centre of mass, floor frame (y up)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();     // m/s, centre of mass
};

inline constexpr int kFlightStateSize = 13;
using FlightStateVec = Eigen::Matrix<double, kFlightStateSize, 1>;
// q = (w, x, y, z), omegaBody, centre, velocity.
enum FlightStateIndex : int { kFlightQw = 0, kFlightOmega = 4, kFlightCentre = 7, kFlightVelocity = 10 };

FlightStateVec toVector(const FlightState& state);
// q read as q / |q|, as in the quaternion formulation.
FlightState toFlightState(const FlightStateVec& y);

// dy/dt: eqs. (1.1)-(1.3), with the quaternion formulation's pull back to |q| = 1.
FlightStateVec flightRhs(const CoinModel& model, const FlightStateVec& y);

// The free flight in closed form (eq. 1.4 and G's parabola): the state `elapsed` seconds after
// `start`, exact to round-off however long the flight, at the cost of a few rotations.
FlightState flightAfter(const CoinModel& model, const FlightState& start, double elapsed);

// m, the radius of the sphere about G that holds the whole coin: no attitude puts the rim's lowest
// point deeper below G than this, so a centre higher above the floor cannot touch it.
double reachBelowCentre(const CoinModel& model);

// J, the energy of the coin standing still upright on its rim, M g h(0) with h from (2.1): every
// attitude with theta = 0, touching the floor or above it, has at least this much (docs/flight.md §5a).
double uprightEnergy(const CoinModel& model);

// m, the height of the rim's lowest point below the centre of mass (eq. 2.1), at every attitude,
// flat included (where it is h/2).
double lowestPointDepth(const CoinModel& model, const Eigen::Quaterniond& unitQ);

// m, the gap between the rim's lowest point and the floor (eq. 2.2): zero at touch, negative inside.
double rimGap(const CoinModel& model, const FlightState& state);

// r, m: from the centre of mass to the rim's lowest point, floor components (docs/rim.md eq. 3.1).
// Flat, where every point of the face's edge is lowest, the one along the body's b2 axis.
Eigen::Vector3d lowestPointVector(const CoinModel& model, const Eigen::Quaterniond& unitQ);

// The velocity of the material point at r, m/s: v + omega x r.
Eigen::Vector3d pointVelocity(const FlightState& state, const Eigen::Vector3d& r);

// The forward pass in flight: no reaction, no loads, dOmega from Euler's equations (material
// components), the contact point the rim's lowest point (above the floor), Forward::flying set.
Forward flightForward(const CoinModel& model, const FlightState& state);

// Kinetic energy, J.
double kineticEnergy(const CoinModel& model, const FlightState& state);

// Angular momentum about the centre of mass, floor components, kg m^2/s.
Eigen::Vector3d angularMomentum(const CoinModel& model, const FlightState& state);

}  // namespace coinroll::physics
